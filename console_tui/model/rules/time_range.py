"""Time range: stamps from ``start`` to ``end`` (both included), either end open."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..store.log_store import Chunk, LogStore
from ..timefmt import full_text
from .fields import read_int
from .rule import Rule, RuleError, SpanTest, mask_and


@dataclass(frozen=True)
class TimeRangeRule(Rule):
    """Matches records stamped ``start_ns <= stamp <= end_ns``; ``None`` leaves that end open."""

    kind = "time"

    start_ns: int | None = None
    end_ns: int | None = None

    def __post_init__(self) -> None:
        if self.start_ns is not None and self.end_ns is not None and self.start_ns > self.end_ns:
            raise RuleError("time range: the start is after the end")

    @property
    def is_empty(self) -> bool:
        return self.start_ns is None and self.end_ns is None

    def compile(self, store: LogStore) -> SpanTest:
        start, end = self.start_ns, self.end_ns

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            stamps = chunk.stamps[lo:hi]
            after = bytes(map(start.__le__, stamps)) if start is not None else None
            before = bytes(map(end.__ge__, stamps)) if end is not None else None
            if after is not None and before is not None:
                return mask_and(after, before)
            return after if after is not None else before  # type: ignore[return-value]

        return test

    def describe(self, *, utc: bool = False) -> str:
        start = full_text(self.start_ns, utc=utc) if self.start_ns is not None else "…"
        end = full_text(self.end_ns, utc=utc) if self.end_ns is not None else "…"
        return f"time {start} to {end}"

    def to_dict(self) -> dict[str, Any]:
        fields: dict[str, Any] = {"kind": self.kind}
        if self.start_ns is not None:
            fields["start_ns"] = self.start_ns
        if self.end_ns is not None:
            fields["end_ns"] = self.end_ns
        return fields

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> TimeRangeRule:
        return cls(read_int(fields, "start_ns"), read_int(fields, "end_ns"))
