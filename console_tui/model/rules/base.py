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
from itertools import compress, repeat
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
            pattern = self.pattern()
            literal = required_literal(pattern)
            return _RegexMasker(pattern, _RowFinder(literal, bool(pattern.flags & re.IGNORECASE)) if literal else None)
        if self.ignore_case:
            folded = self.text.casefold()
            finder = _RowFinder(folded, True)
            return lambda strings: finder(strings) or bytes(map(contains, map(str.casefold, strings), repeat(folded)))
        text = self.text
        return lambda strings: bytes(map(contains, strings, repeat(text)))

    def describe(self) -> str:
        options = [name for name, on in (("regex", self.regex), ("ignore case", self.ignore_case)) if on]
        shown = f"/{self.text}/" if self.regex else repr(self.text)
        return shown + (f" ({', '.join(options)})" if options else "")


def required_literal(pattern: re.Pattern[str]) -> str:
    """The longest run of plain characters every match of ``pattern`` contains ("" if none
    is known): a fast ``str.find`` over many messages then leaves few for the regex."""
    try:
        from re import _parser as parser  # Python 3.11+
    except ImportError:  # pragma: no cover - Python 3.10
        import sre_parse as parser  # type: ignore[no-redef]
    try:
        items = list(parser.parse(pattern.pattern, pattern.flags & ~re.UNICODE))
    except Exception:  # noqa: BLE001 - an internal API: no literal rather than an error
        return ""
    best, run = "", []
    for op, argument in items + [(None, None)]:
        if str(op) == "LITERAL":
            run.append(chr(argument))
            continue
        if len(run) > len(best):
            best = "".join(run)
        run = []
    return best


class _RowFinder:
    """Which of many strings contain ``needle``, found by ``str.find`` over them all joined.

    Case-insensitive finding lowers the joined text once, which equals case folding only for
    ASCII text: ``__call__`` returns None when it cannot answer (non-ASCII text or needle,
    or a string holding the separator) and the caller tests string by string.
    """

    __slots__ = ("_needle", "_ignore_case")

    def __init__(self, needle: str, ignore_case: bool) -> None:
        self._needle = needle.lower() if ignore_case else needle
        self._ignore_case = ignore_case

    def __call__(self, strings: list[str]) -> bytes | None:
        needle = self._needle
        if _SEPARATOR in needle or (self._ignore_case and not needle.isascii()):
            return None
        joined = _SEPARATOR.join(strings)
        if self._ignore_case:
            if not joined.isascii():
                return None
            joined = joined.lower()
        if joined.count(_SEPARATOR) != len(strings) - 1:
            return None
        mask = bytearray(len(strings))
        find, count = joined.find, joined.count
        row, counted_to = 0, 0  # ``row`` is the row that position ``counted_to`` is in
        position = find(needle)
        while position >= 0:
            row += count(_SEPARATOR, counted_to, position)
            mask[row] = 1
            row_end = find(_SEPARATOR, position)
            if row_end < 0:
                break
            row, counted_to = row + 1, row_end + 1
            position = find(needle, counted_to)
        return bytes(mask)


class _RegexMasker:
    """Regex masks; with a required literal, only strings that contain it are searched."""

    __slots__ = ("_search", "_finder")

    def __init__(self, pattern: re.Pattern[str], finder: _RowFinder | None) -> None:
        self._search = pattern.search
        self._finder = finder

    def __call__(self, strings: list[str]) -> bytes:
        search = self._search
        candidates = self._finder(strings) if self._finder is not None else None
        if candidates is None:
            return bytes(map(bool, map(search, strings)))
        mask = bytearray(len(strings))
        for row in compress(range(len(strings)), candidates):
            if search(strings[row]) is not None:
                mask[row] = 1
        return bytes(mask)
