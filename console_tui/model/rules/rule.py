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

from array import array
from collections.abc import Callable, Iterable, Mapping
from typing import Any, ClassVar

from ..store.log_store import Chunk, LogStore, StringTable
from ..store.record import LogRecord

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
    #: Each kind's fields (every kind is a dataclass).
    __dataclass_fields__: ClassVar[dict[str, Any]]

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

    __slots__ = ("_answers", "_predicate", "_table")

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
            # Ids fit in the low byte of each id (2 or 4 bytes): one C-level translate.
            low_bytes = ids[lo:hi].tobytes()[0 :: ids.itemsize]
            return low_bytes.translate(bytes(answers) + bytes(256 - len(answers)))
        return bytes(map(answers.__getitem__, ids[lo:hi]))


def mask_of_rows(rows: Iterable[int], size: int) -> bytes:
    mask = bytearray(size)
    for row in rows:
        mask[row] = 1
    return bytes(mask)
