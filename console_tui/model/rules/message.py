"""Message text: a substring or a regular expression, optionally ignoring case."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..store import Chunk, LogStore
from .fields import read_bool, read_str
from .rule import Rule, SpanTest
from .text_match import TextMatch


@dataclass(frozen=True)
class MessageRule(Rule):
    """Matches records whose message contains ``text`` (or where the regex ``text`` is found)."""

    kind = "message"

    text: str = ""
    ignore_case: bool = False
    regex: bool = False

    def __post_init__(self) -> None:
        self.match  # noqa: B018 - validates the regex

    @property
    def match(self) -> TextMatch:
        return TextMatch(self.text, self.ignore_case, self.regex)

    @property
    def is_empty(self) -> bool:
        return self.text == ""

    def compile(self, store: LogStore) -> SpanTest:
        mask_of = self.match.mask_function()

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            return mask_of(chunk.msgs[lo:hi])

        return test

    def describe(self) -> str:
        return f"message {self.match.describe()}"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "text": self.text, "ignore_case": self.ignore_case, "regex": self.regex}

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> MessageRule:
        return cls(read_str(fields, "text"), read_bool(fields, "ignore_case"), read_bool(fields, "regex"))
