"""Many messages in one string: what a full chunk of the store keeps its messages as.

A ``str`` object costs 49 bytes before its text and a list 8 more for pointing at it:
for a log message of 90 characters that is 40% of its memory. ``PackedTexts`` keeps a
full chunk's messages joined by NUL in one string, with where each one starts (4 bytes
a message), and is read like a tuple of strings: an index gives one message, a slice a
list of them (one C-level ``split``). Being no container of objects, it also costs
Python's cyclic garbage collector nothing, where a million strings in lists cost it a visit
each (docs/architecture.md, "The store keeps full chunks packed").

Reading a slice makes a ``str`` for each text, so the last few chunks read whole are kept
as lists for a while (``RECENT``): filtering reads a chunk in several slices, once per rule,
and pays for the texts once.

``pack`` chooses: texts that hold NUL themselves, or non-ASCII texts that would take
more room joined (one wide character widens the whole string), stay a list.
"""

from __future__ import annotations

import sys
from array import array
from collections import deque
from collections.abc import Iterator, Sequence
from itertools import accumulate, repeat
from operator import add
from typing import overload

_SEPARATOR = "\0"
_OFFSET_LIMIT = (1 << 32) - 1
#: How many chunks' texts are kept as lists after being read (a few MB at most).
RECENT = 4
_recent: deque[PackedTexts] = deque()


class PackedTexts(Sequence[str]):
    """Texts joined by NUL in ``text``; text ``i`` is ``text[starts[i] : starts[i + 1] - 1]``.

    ``text`` and ``starts`` are there to be searched directly (all texts at once)."""

    __slots__ = ("_texts", "starts", "text")

    def __init__(self, text: str, starts: array) -> None:
        self.text = text
        #: Where each text starts, and one past the end: ``len(text) + 1``.
        self.starts = starts
        self._texts: list[str] | None = None

    def texts(self) -> list[str]:
        """Every text, as a list (kept while this is one of the ``RECENT`` chunks read)."""
        texts = self._texts
        if texts is None:
            texts = self._texts = self.text.split(_SEPARATOR) if len(self.starts) > 1 else []
            _recent.append(self)
            if len(_recent) > RECENT:
                _recent.popleft()._texts = None
        return texts

    def __len__(self) -> int:
        return len(self.starts) - 1

    @overload
    def __getitem__(self, index: int) -> str: ...

    @overload
    def __getitem__(self, index: slice) -> list[str]: ...

    def __getitem__(self, index: int | slice) -> str | list[str]:
        starts = self.starts
        if isinstance(index, slice):
            count = len(starts) - 1
            lo, hi, step = index.indices(count)
            if step != 1 or self._texts is not None or 4 * (hi - lo) >= count:
                return self.texts()[index]
            if lo >= hi:
                return []
            return self.text[starts[lo] : starts[hi] - 1].split(_SEPARATOR)
        if index < 0:
            index += len(starts) - 1
        return self.text[starts[index] : starts[index + 1] - 1]

    def __iter__(self) -> Iterator[str]:
        return iter(self.texts())

    def __eq__(self, other: object) -> bool:
        if isinstance(other, PackedTexts):
            return self.text == other.text and self.starts == other.starts
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]


def pack(texts: list[str]) -> list[str] | PackedTexts:
    """``texts`` as ``PackedTexts`` where that takes less memory, else as they are."""
    if not texts:
        return texts
    joined = _SEPARATOR.join(texts)
    if joined.count(_SEPARATOR) != len(texts) - 1 or len(joined) >= _OFFSET_LIMIT:
        return texts
    if not joined.isascii():
        apart = sum(map(sys.getsizeof, texts)) + 8 * len(texts)
        if sys.getsizeof(joined) + 4 * len(texts) >= apart:
            return texts
    starts = array("I", accumulate(map(add, map(len, texts), repeat(1)), initial=0))
    return PackedTexts(joined, starts)
