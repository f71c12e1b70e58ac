"""Custom: several rules of the other kinds that must all match (rqt_console's Custom filter)."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from itertools import compress
from typing import Any

from ..store.log_store import Chunk, LogStore
from .message import MessageRule, messages_test
from .rule import Rule, RuleError, SpanTest, all_of, mask_and


@dataclass(frozen=True)
class CustomRule(Rule):
    """Matches records that every non-empty part matches; empty when all parts are empty."""

    kind = "custom"

    parts: tuple[Rule, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "parts", tuple(self.parts))
        for part in self.parts:
            if not isinstance(part, Rule) or isinstance(part, CustomRule):
                raise RuleError("custom rule: parts must be message, severity, node, location or time rules")

    @property
    def is_empty(self) -> bool:
        return all(part.is_empty for part in self.parts)

    def compile(self, store: LogStore) -> SpanTest:
        """Column tests first; message text last, and then only on the records still in."""
        parts = [part for part in self.parts if not part.is_empty]
        columns = [part.compile(store) for part in parts if not isinstance(part, MessageRule)]
        texts = [
            (part.match.mask_function(), messages_test(part.match)) for part in parts if isinstance(part, MessageRule)
        ]

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            size = hi - lo
            mask = all_of((part(chunk, lo, hi) for part in columns), size)
            for mask_of, span_test in texts:
                candidates = mask.count(1)
                if candidates == 0:
                    break
                if candidates * 4 > size:
                    mask = mask_and(mask, span_test(chunk, lo, hi))
                    continue
                rows = list(compress(range(size), mask))
                msgs = chunk.msgs
                narrowed = bytearray(size)
                for row, hit in zip(rows, mask_of([msgs[lo + row] for row in rows]), strict=False):
                    narrowed[row] = hit
                mask = bytes(narrowed)
            return mask

        return test

    def describe(self) -> str:
        return " and ".join(part.describe() for part in self.parts if not part.is_empty) or "custom (empty)"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "parts": [part.to_dict() for part in self.parts]}

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> CustomRule:
        from .ruleset import rule_from_dict

        parts = fields.get("parts", [])
        if not isinstance(parts, list):
            raise RuleError("parts: expected a list of rules")
        return cls(tuple(rule_from_dict(part, f"parts[{i}]") for i, part in enumerate(parts)))
