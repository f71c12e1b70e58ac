"""What every rule kind shares: the error type, the rule base class, match masks.

A rule is a frozen, hashable value (what it tests, never whether it is on): a rule set
wraps each in an ``Entry`` that says exclude or highlight, enabled, inverted.

Rules test the columnar store a span at a time. ``Rule.compile(store)`` gives a
``SpanTest``: ``test(chunk, lo, hi)`` returns one byte per record of ``chunk[lo:hi]``,
1 where the rule matches and 0 where not. Masks are combined with C-speed integer
operations (``mask_and`` ...), and per-string-id lookups (``IdLookup``) evaluate node,
file and function predicates once per distinct string instead of once per record.
"""

from __future__ import annotations

import re
from array import array
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from itertools import repeat
from operator import contains
from typing import Any, ClassVar

from ..record import LogRecord
from ..store import Chunk, LogStore, StringTable

#: ``test(chunk, lo, hi)``: one byte per record of ``chunk[lo:hi]``, 1 where it matches.
SpanTest = Callable[[Chunk, int, int], bytes]

_NOT = bytes([1, 0]) + bytes(254)


class RuleError(ValueError):
    """A rule (or query, or rules file) that cannot be used; ``position`` points into its text."""

    def __init__(self, message: str, position: int | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.position = position


def mask_and(a: bytes, b: bytes) -> bytes:
    return (int.from_bytes(a, "little") & int.from_bytes(b, "little")).to_bytes(len(a), "little")


def mask_or(a: bytes, b: bytes) -> bytes:
    return (int.from_bytes(a, "little") | int.from_bytes(b, "little")).to_bytes(len(a), "little")


def mask_not(a: bytes) -> bytes:
    return a.translate(_NOT)


def all_of(masks: Iterable[bytes], size: int) -> bytes:
    result = b"\x01" * size
    for mask in masks:
        result = mask_and(result, mask)
    return result


class Rule:
    """Base of the rule kinds. Subclasses are frozen dataclasses with a unique ``kind``."""

    kind: ClassVar[str] = ""
    #: Rule classes by ``kind``, for reading rule files.
    kinds: ClassVar[dict[str, type[Rule]]] = {}

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if cls.kind:
            Rule.kinds[cls.kind] = cls

    @property
    def is_empty(self) -> bool:
        """A rule with no input matches nothing (and does not count as active)."""
        raise NotImplementedError

    def compile(self, store: LogStore) -> SpanTest:
        raise NotImplementedError

    def describe(self) -> str:
        """One line for the rules pane."""
        raise NotImplementedError

    def to_dict(self) -> dict[str, Any]:
        """Plain values for a rules file (``kind`` included)."""
        raise NotImplementedError

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> Rule:
        """The inverse of ``to_dict`` without ``kind``; ``RuleError`` naming a bad field."""
        raise NotImplementedError

    def matches(self, record: LogRecord) -> bool:
        """Test one record (convenience; the view tests spans)."""
        if self.is_empty:
            return False
        store = LogStore(1)
        store.append(record)
        span = next(store.spans(0, 1))
        return self.compile(store)(span.chunk, span.lo, span.hi) == b"\x01"


class IdLookup:
    """A predicate over a string table, evaluated once per distinct string.

    Masks come from the ids in a chunk column; the table of answers grows with the table.
    """

    __slots__ = ("_table", "_predicate", "_answers")

    def __init__(self, table: StringTable, predicate: Callable[[str], object]) -> None:
        self._table = table
        self._predicate = predicate
        self._answers = bytearray()

    def mask(self, ids: array, lo: int, hi: int) -> bytes:
        answers, table = self._answers, self._table
        if len(answers) < len(table):
            predicate = self._predicate
            answers.extend(1 if predicate(table[i]) else 0 for i in range(len(answers), len(table)))
        if len(answers) <= 256:
            # Ids fit in the low byte of each 4-byte id: one C-level translate.
            low_bytes = ids[lo:hi].tobytes()[0 :: ids.itemsize]
            return low_bytes.translate(bytes(answers) + bytes(256 - len(answers)))
        return bytes(map(answers.__getitem__, ids[lo:hi]))


_SEPARATOR = "\x00"


@dataclass(frozen=True)
class TextMatch:
    """Text to look for in a string: a substring, or a regex (``re.search``), either case."""

    text: str = ""
    ignore_case: bool = False
    regex: bool = False

    def __post_init__(self) -> None:
        if self.regex and self.text:
            self.pattern()  # raises RuleError now rather than while filtering

    @property
    def is_empty(self) -> bool:
        return self.text == ""

    def pattern(self) -> re.Pattern[str]:
        try:
            return re.compile(self.text, re.IGNORECASE if self.ignore_case else 0)
        except re.error as error:
            where = f" at position {error.pos}" if error.pos is not None else ""
            raise RuleError(f"invalid regular expression {self.text!r}: {error.msg}{where}", error.pos) from None
        except (OverflowError, RecursionError) as error:
            raise RuleError(f"invalid regular expression {self.text!r}: {error}", None) from None

    def predicate(self) -> Callable[[str], bool]:
        """``str -> bool`` (for per-id lookups)."""
        if self.regex:
            search = self.pattern().search
            return lambda value: search(value) is not None
        if self.ignore_case:
            folded = self.text.casefold()
            return lambda value: folded in value.casefold()
        text = self.text
        return lambda value: text in value

    def mask_function(self) -> Callable[[list[str]], bytes]:
        """``strings -> mask``, the fastest way this kind of match allows."""
        if self.regex:
            search = self.pattern().search
            return lambda strings: bytes(map(bool, map(search, strings)))
        if self.ignore_case:
            return _CaselessFinder(self.text.casefold())
        text = self.text
        return lambda strings: bytes(map(contains, strings, repeat(text)))

    def describe(self) -> str:
        options = [name for name, on in (("regex", self.regex), ("ignore case", self.ignore_case)) if on]
        shown = f"/{self.text}/" if self.regex else repr(self.text)
        return shown + (f" ({', '.join(options)})" if options else "")


class _CaselessFinder:
    """Case-insensitive substring masks (``casefold`` semantics).

    Mostly-ASCII logs take a fast path: the strings joined, lowered once, and searched
    with ``str.find``; for ASCII text ``lower`` is ``casefold`` and keeps offsets.
    """

    __slots__ = ("_folded",)

    def __init__(self, folded: str) -> None:
        self._folded = folded

    def __call__(self, strings: list[str]) -> bytes:
        folded = self._folded
        joined = _SEPARATOR.join(strings)
        if not joined.isascii() or joined.count(_SEPARATOR) != len(strings) - 1 or _SEPARATOR in folded:
            return bytes(map(contains, map(str.casefold, strings), repeat(folded)))
        lowered = joined.lower()
        mask = bytearray(len(strings))
        find, count = lowered.find, lowered.count
        row, counted_to = 0, 0  # ``row`` is the row that position ``counted_to`` is in
        position = find(folded)
        while position >= 0:
            row += count(_SEPARATOR, counted_to, position)
            mask[row] = 1
            row_end = find(_SEPARATOR, position)
            if row_end < 0:
                break
            row, counted_to = row + 1, row_end + 1
            position = find(folded, counted_to)
        return bytes(mask)
