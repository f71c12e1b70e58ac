"""Message text: a substring or a regular expression, optionally ignoring case."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..store.log_store import Chunk, LogStore
from ..store.packed_texts import PackedTexts
from .fields import read_bool, read_str
from .pattern_match import TextMatch
from .rule import Rule, SpanTest

#: Spans tested message by message after the packed way could not answer one.
SKIP_AFTER_MISS = 8


def messages_test(match: TextMatch) -> SpanTest:
    """``match`` over the messages of a span: on the packed text of a full chunk all at once
    where the match allows (``packed_match``), else message by message."""
    mask_of = match.mask_function()
    packed = match.packed_matcher()
    skip = 0

    def test(chunk: Chunk, lo: int, hi: int) -> bytes:
        nonlocal skip
        msgs = chunk.msgs
        if packed is not None and isinstance(msgs, PackedTexts):
            if skip:
                skip -= 1
            else:
                mask = packed(msgs, lo, hi)
                if mask is not None:
                    return mask
                skip = SKIP_AFTER_MISS  # the next chunks are likely alike: don't try for a while
        return mask_of(msgs[lo:hi])

    return test


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
        return messages_test(self.match)

    def describe(self) -> str:
        return f"message {self.match.describe()}"

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "text": self.text, "ignore_case": self.ignore_case, "regex": self.regex}

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> MessageRule:
        return cls(read_str(fields, "text"), read_bool(fields, "ignore_case"), read_bool(fields, "regex"))
