"""Severity: a set of message severities (levels between steps count under the one below)."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from ..levels import MESSAGE_SEVERITIES, parse_severity, severity_bucket, severity_name
from ..store.log_store import Chunk, LogStore
from .fields import read_str_list
from .rule import Rule, RuleError, SpanTest


@dataclass(frozen=True)
class SeverityRule(Rule):
    """Matches records whose severity is one of ``levels`` (ROS 2 numbers: 10 .. 50)."""

    kind = "severity"

    levels: frozenset[int] = frozenset()

    def __post_init__(self) -> None:
        levels = frozenset(int(level) for level in self.levels)
        unknown = sorted(levels - {int(s) for s in MESSAGE_SEVERITIES})
        if unknown:
            raise RuleError(f"not a message severity: {unknown[0]}")
        object.__setattr__(self, "levels", levels)

    @classmethod
    def of(cls, *names: str) -> SeverityRule:
        """``SeverityRule.of("warn", "error")``."""
        return cls(frozenset(parse_severity(name) for name in names))

    @classmethod
    def at_least(cls, level: int) -> SeverityRule:
        return cls(frozenset(int(s) for s in MESSAGE_SEVERITIES if s >= level))

    @classmethod
    def at_most(cls, level: int) -> SeverityRule:
        return cls(frozenset(int(s) for s in MESSAGE_SEVERITIES if s <= level))

    @property
    def is_empty(self) -> bool:
        return not self.levels

    def compile(self, store: LogStore) -> SpanTest:
        table = bytes(1 if severity_bucket(level) in self.levels else 0 for level in range(256))

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            return chunk.levels[lo:hi].tobytes().translate(table)

        return test

    def names(self) -> list[str]:
        return [severity_name(level).lower() for level in sorted(self.levels)]

    def describe(self) -> str:
        return "severity " + ", ".join(name.upper() for name in self.names())

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "levels": self.names()}

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> SeverityRule:
        return cls(frozenset(_parse_levels(read_str_list(fields, "levels"))))


def _parse_levels(names: Iterable[str]) -> Iterable[int]:
    for name in names:
        try:
            yield int(parse_severity(name))
        except ValueError as error:
            raise RuleError(f"levels: {error}") from None
