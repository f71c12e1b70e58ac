"""Robot: the robot of a fleet a record came from, by name or glob (``picker``, ``arm*``)."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from fnmatch import translate
from typing import Any

from ..store import Chunk, LogStore
from .fields import read_str_list
from .node import is_glob
from .rule import IdLookup, Rule, SpanTest


@dataclass(frozen=True)
class RobotRule(Rule):
    """Matches records from any of ``names``: robots' names or globs (case-sensitive).
    Records that name no robot (one source, not a fleet) match none."""

    kind = "robot"

    names: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        names = (self.names,) if isinstance(self.names, str) else self.names
        object.__setattr__(self, "names", tuple(n.strip() for n in names if n.strip()))

    @property
    def is_empty(self) -> bool:
        return not self.names

    def predicate(self) -> Callable[[str], bool]:
        exact = {name for name in self.names if not is_glob(name)}
        globs = [translate(name) for name in self.names if is_glob(name)]
        match = re.compile("|".join(globs)).match if globs else None

        def test_name(name: str) -> bool:
            return bool(name) and (name in exact or (match is not None and match(name) is not None))

        return test_name

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
