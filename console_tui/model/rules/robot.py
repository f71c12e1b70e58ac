"""Robot: the robot of a fleet a record came from, by name or glob (``picker``, ``arm*``)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from ..store import Chunk, LogStore
from .fields import read_str_list
from .node import clean_names, names_predicate
from .rule import IdLookup, Rule, SpanTest


@dataclass(frozen=True)
class RobotRule(Rule):
    """Matches records from any of ``names``: robots' names or globs (case-sensitive).
    Records that name no robot (one source, not a fleet) match none."""

    kind = "robot"

    names: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "names", clean_names(self.names))

    @property
    def is_empty(self) -> bool:
        return not self.names

    def predicate(self) -> Callable[[str], bool]:
        test = names_predicate(self.names)
        return lambda name: bool(name) and test(name)

    def compile(self, store: LogStore) -> SpanTest:
        lookup = IdLookup(store.robots, self.predicate())

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            robots = chunk.robots
            return bytes(hi - lo) if robots is None else lookup.mask(robots, lo, hi)

        return test

    def describe(self) -> str:
        return "robot " + ", ".join(self.names)

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "names": list(self.names)}

    @classmethod
    def from_fields(cls, fields: Mapping[str, Any]) -> RobotRule:
        return cls(read_str_list(fields, "names"))
