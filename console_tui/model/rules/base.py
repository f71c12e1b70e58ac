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
import sys
from array import array
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, replace
from itertools import chain, compress, repeat
from operator import add, contains, sub
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
            return _RegexMasker(self.pattern())
        if self.ignore_case:
            folded = self.text.casefold()
            return lambda strings: bytes(map(contains, map(str.casefold, strings), repeat(folded)))
        text = self.text
        return lambda strings: bytes(map(contains, strings, repeat(text)))

    def describe(self) -> str:
        options = [name for name, on in (("regex", self.regex), ("ignore case", self.ignore_case)) if on]
        shown = f"/{self.text}/" if self.regex else repr(self.text)
        return shown + (f" ({', '.join(options)})" if options else "")


@dataclass(frozen=True)
class RequiredLiteral:
    """Plain text every match of a regex contains, and where matches can lie around it.

    ``lead`` and ``tail``: at most how many characters a match holds before and after the
    text (None: unbounded, or, for ``tail``, a pattern whose answer depends on what lies
    outside the match: anchors, ``\\b``, lookarounds).
    """

    text: str = ""
    lead: int | None = None
    tail: int | None = None


_MAX_WIDTH = 10_000
_CONTEXT_OPS = frozenset({"AT", "ASSERT", "ASSERT_NOT"})


def required_literal(pattern: re.Pattern[str]) -> RequiredLiteral:
    """The longest run of plain characters every match of ``pattern`` contains, if any.

    A fast ``in`` over many messages then leaves few for the regex, and those are searched
    only around the run's occurrences."""
    try:
        from re import _parser as parser  # Python 3.11+
    except ImportError:  # pragma: no cover - Python 3.10
        import sre_parse as parser  # type: ignore[no-redef]
    try:
        parsed = parser.parse(pattern.pattern, pattern.flags & ~re.UNICODE)
        items = list(parsed)
        best, best_start, run = "", 0, []
        for index, (op, argument) in enumerate(items + [(None, None)]):
            if str(op) == "LITERAL":
                run.append(chr(argument))
                continue
            if len(run) > len(best):
                best, best_start = "".join(run), index - len(run)
            run = []
        _, lead = parser.SubPattern(parsed.state, items[:best_start]).getwidth()
        _, tail = parser.SubPattern(parsed.state, items[best_start + len(best) :]).getwidth()
    except Exception:  # noqa: BLE001 - an internal API: no literal rather than an error
        return RequiredLiteral()
    return RequiredLiteral(
        best,
        lead if lead < _MAX_WIDTH else None,
        tail if tail < _MAX_WIDTH and not _uses_context(items) else None,
    )


def _uses_context(node: object) -> bool:
    """Whether a parsed regex holds an op that looks outside the matched text."""
    if isinstance(node, tuple) and len(node) == 2 and str(node[0]) in _CONTEXT_OPS:
        return True
    if isinstance(node, (list, tuple)):
        return any(map(_uses_context, node))
    data = getattr(node, "data", None)  # a SubPattern
    return isinstance(data, list) and _uses_context(data)


def mask_of_rows(rows: Iterable[int], size: int) -> bytes:
    mask = bytearray(size)
    for row in rows:
        mask[row] = 1
    return bytes(mask)


class _RegexMasker:
    """Regex masks. With a required literal, only strings that contain it are searched, and
    only around its occurrences (from the first one less the lead, to the last one plus the
    tail) where those are bounded.

    Ignoring case, the literal is looked for in lower-cased text, which is exact for an ASCII
    literal in ASCII text; other strings are searched whole, and a non-ASCII literal is not used.
    """

    __slots__ = ("_ignore_case", "_literal", "_search")

    def __init__(self, pattern: re.Pattern[str]) -> None:
        self._search = pattern.search
        self._ignore_case = bool(pattern.flags & re.IGNORECASE)
        literal = required_literal(pattern)
        if self._ignore_case:
            literal = replace(literal, text=literal.text.lower()) if literal.text.isascii() else RequiredLiteral()
        self._literal = literal

    def __call__(self, strings: list[str]) -> bytes:
        search, literal = self._search, self._literal
        text = literal.text
        if not text:
            return bytes(map(bool, map(search, strings)))
        everything = range(len(strings))
        searched_whole: list[int] = []
        if self._ignore_case:
            haystacks = list(map(str.lower, strings))
            ascii_only = bytes(map(str.isascii, strings))
            searched_whole = list(compress(everything, mask_not(ascii_only)))
            candidates = mask_and(bytes(map(contains, haystacks, repeat(text))), ascii_only)
        else:
            haystacks = strings
            candidates = bytes(map(contains, strings, repeat(text)))
        # C-level loops over the candidates (``map``), a Python one only over the matches.
        rows = list(compress(everything, candidates))
        starts: Iterable[int] = repeat(0)
        ends: Iterable[int] = repeat(sys.maxsize)
        if literal.lead is not None:
            firsts = map(str.find, map(haystacks.__getitem__, rows), repeat(text))
            starts = map(max, map(sub, firsts, repeat(literal.lead)), repeat(0))
        if literal.tail is not None:
            lasts = map(str.rfind, map(haystacks.__getitem__, rows), repeat(text))
            ends = map(add, lasts, repeat(len(text) + literal.tail))
        found = compress(rows, map(search, map(strings.__getitem__, rows), starts, ends))
        whole = compress(searched_whole, map(search, map(strings.__getitem__, searched_whole)))
        return mask_of_rows(chain(found, whole), len(strings))
