"""Robot: the robot of a fleet a record came from, by name or glob (``picker``, ``arm*``)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ..store.log_store import Chunk, LogStore
from .node import NamesRule, names_predicate
from .rule import IdLookup, SpanTest


@dataclass(frozen=True)
class RobotRule(NamesRule):
    """Matches records from any of ``names``: robots' names or globs (case-sensitive).
    Records that name no robot (one source, not a fleet) match none."""

    kind = "robot"

    def predicate(self) -> Callable[[str], bool]:
        test = names_predicate(self.names)
        return lambda name: bool(name) and test(name)

    def compile(self, store: LogStore) -> SpanTest:
        lookup = IdLookup(store.robots, self.predicate())

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            robots = chunk.robots
            return bytes(hi - lo) if robots is None else lookup.mask(robots, lo, hi)

        return test
