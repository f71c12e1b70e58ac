"""Location: file, function and line where the message was logged."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..store.log_store import Chunk, LogStore
from .fields import read_bool, read_int, read_str
from .pattern_match import TextMatch
from .rule import IdLookup, Rule, RuleError, SpanTest, all_of


@dataclass(frozen=True)
class LocationRule(Rule):
    """Matches records whose file and function contain the given text (or regexes) and whose
    line is ``line``; the parts left empty are not tested."""

    kind = "location"

    file: str = ""
    function: str = ""
    line: int | None = None
    regex: bool = False
    ignore_case: bool = False

    def __post_init__(self) -> None:
        if self.line is not None and not 0 <= self.line <= 0xFFFFFFFF:
            raise RuleError(f"line: not a line number: {self.line}")
        for part in (self.file, self.function):
            TextMatch(part, self.ignore_case, self.regex)  # validates regexes

    @property
    def is_empty(self) -> bool:
        return not self.file and not self.function and self.line is None

    def compile(self, store: LogStore) -> SpanTest:
        tests = []
        if self.file:
            files = IdLookup(store.files, TextMatch(self.file, self.ignore_case, self.regex).predicate())
            tests.append(lambda chunk, lo, hi: files.mask(chunk.files, lo, hi))
        if self.function:
            functions = IdLookup(store.functions, TextMatch(self.function, self.ignore_case, self.regex).predicate())
            tests.append(lambda chunk, lo, hi: functions.mask(chunk.functions, lo, hi))
        if self.line is not None:
            is_line = self.line.__eq__
            tests.append(lambda chunk, lo, hi: bytes(map(is_line, chunk.lines[lo:hi])))

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            return all_of((part(chunk, lo, hi) for part in tests), hi - lo)

        return test

    def describe(self) -> str:
        parts = []
        for name, text in (("file", self.file), ("function", self.function)):
            if text:
                parts.append(f"{name} {TextMatch(text, self.ignore_case, self.regex).describe()}")
        if self.line is not None:
            parts.append(f"line {self.line}")
        return "location " + " ".join(parts)

    def to_dict(self) -> dict[str, Any]:
        fields: dict[str, Any] = {"kind": self.kind, "file": self.file, "function": self.function}
        if self.line is not None:
            fields["line"] = self.line
        fields.update(regex=self.regex, ignore_case=self.ignore_case)
        return fields

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> LocationRule:
        return cls(
            read_str(fields, "file"),
            read_str(fields, "function"),
            read_int(fields, "line"),
            read_bool(fields, "regex"),
            read_bool(fields, "ignore_case"),
        )
