"""Many messages in one string, kept compressed: what a full chunk of the store keeps its messages as.

``PackedTexts`` keeps a full chunk's messages joined by NUL, as UTF-8 compressed with LZ4, with
where each one starts (4 bytes a message), and is read like a tuple of strings: an index gives
one message, a slice a list of them (one C-level ``split``). It holds no Python container, so
the cyclic garbage collector never visits it. Reading decompresses the chunk's joined text, and
reading a slice makes a ``str`` for each text, so the last few chunks read (``RECENT``) keep what
was made for a while: filtering reads a chunk in several slices, once per rule, and the table
draws the same rows frame after frame. ``pack`` leaves texts that hold NUL themselves as a list.
Why, and what it costs: docs/decisions/0008-compressed-chunk-texts.md.
"""

from __future__ import annotations

from array import array
from collections import deque
from collections.abc import Iterator, Sequence
from itertools import accumulate, repeat
from operator import add
from typing import overload

_SEPARATOR = "\0"
#: The most UTF-8 bytes packed: LZ4's block limit (a character offset is at most its byte offset).
_SIZE_LIMIT = 0x7E000000
#: How many chunks keep their texts decompressed (and split, once read as a list) after being read:
#: a few MB at most.
RECENT = 4
_recent: deque[PackedTexts] = deque()


class PackedTexts(Sequence[str]):
    """Texts joined by NUL in ``text``; text ``i`` is ``text[starts[i] : starts[i + 1] - 1]``.

    ``text`` (made from the compressed form when no recent reader made it) and ``starts`` are
    there to be searched directly (all texts at once)."""

    __slots__ = ("_packed", "_text", "_texts", "starts")

    def __init__(self, text: str, starts: array, packed: bytes | None = None) -> None:
        #: The joined text's UTF-8 (lone surrogates kept), LZ4-compressed.
        self._packed = packed if packed is not None else _compressed(text)
        #: Where each text starts, and one past the end: ``len(text) + 1``.
        self.starts = starts
        self._text: str | None = text
        self._texts: list[str] | None = None
        _remember(self)  # just made: the newest records are read first

    @property
    def text(self) -> str:
        """Every text, joined by NUL."""
        text = self._text
        if text is None:
            text = _decompressed(self._packed).decode("utf-8", "surrogatepass")
            if self._texts is None:
                _remember(self)
            self._text = text
        return text

    def texts(self) -> list[str]:
        """Every text, as a list (kept while this is one of the ``RECENT`` chunks read)."""
        texts = self._texts
        if texts is None:
            text = self.text
            texts = self._texts = text.split(_SEPARATOR) if len(self.starts) > 1 else []
        return texts

    @property
    def nbytes(self) -> int:
        """The bytes kept for good: the compressed texts and their starts."""
        return len(self._packed) + self.starts.itemsize * len(self.starts)

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
            return self._packed == other._packed and self.starts == other.starts
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]


def _compressed(text: str) -> bytes:
    return _compress(text.encode("utf-8", "surrogatepass"))


# lz4 is imported when first used: the headless commands (``console-tui loggers`` on a robot's
# Python) import the model without ever packing a chunk.
def _compress(data: bytes) -> bytes:
    from lz4.block import compress

    packed: bytes = compress(data, store_size=True)
    return packed


def _decompressed(packed: bytes) -> bytes:
    from lz4.block import decompress

    data: bytes = decompress(packed)
    return data


def _remember(texts: PackedTexts) -> None:
    """``texts`` made what it keeps while recent; the oldest of the recent ones forgets."""
    _recent.append(texts)
    if len(_recent) > RECENT:
        oldest = _recent.popleft()
        oldest._text = oldest._texts = None


def pack(texts: list[str]) -> list[str] | PackedTexts:
    """``texts`` as ``PackedTexts``, unless one of them holds a NUL (or they are too big)."""
    if not texts:
        return texts
    joined = _SEPARATOR.join(texts)
    if joined.count(_SEPARATOR) != len(texts) - 1:
        return texts
    encoded = joined.encode("utf-8", "surrogatepass")
    if len(encoded) > _SIZE_LIMIT:
        return texts
    starts = array("I", accumulate(map(add, map(len, texts), repeat(1)), initial=0))
    return PackedTexts(joined, starts, _compress(encoded))
