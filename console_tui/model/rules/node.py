"""Node: exact logger names or glob patterns (``nav*``, ``/ns/*``), each maybe of a robot of a
fleet (``picker:/talker``, ``arm*:nav*``: those robots' nodes only)."""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from fnmatch import translate
from typing import Any, TypeVar

from ..loggers.logger_levels import split_robot
from ..store.log_store import Chunk, LogStore
from .fields import read_str_list
from .rule import IdLookup, Rule, SpanTest, mask_and, mask_or

_GLOB_CHARS = frozenset("*?[")


def logger_name(name: str) -> str:
    """A node name as its logger name: ``/ns/talker`` -> ``ns.talker``; logger names unchanged."""
    name = name.strip()
    if name.startswith("/"):
        name = name.lstrip("/").replace("/", ".")
    return name


def is_glob(pattern: str) -> bool:
    return not _GLOB_CHARS.isdisjoint(pattern)


def clean_names(names: str | Iterable[str]) -> tuple[str, ...]:
    """Names or globs as a rule keeps them: one name given alone made a tuple, blanks dropped."""
    return tuple(n.strip() for n in ((names,) if isinstance(names, str) else names) if n.strip())


def names_predicate(patterns: Iterable[str]) -> Callable[[str], bool]:
    """A test of a name against exact names and globs (case-sensitive)."""
    patterns = set(patterns)
    exact = {pattern for pattern in patterns if not is_glob(pattern)}
    globs = [translate(pattern) for pattern in patterns if is_glob(pattern)]
    match = re.compile("|".join(globs)).match if globs else None

    def test_name(name: str) -> bool:
        return name in exact or (match is not None and match(name) is not None)

    return test_name


_Names = TypeVar("_Names", bound="NamesRule")


@dataclass(frozen=True)
class NamesRule(Rule):
    """A rule over names or globs (``names``): what node and robot rules share."""

    names: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "names", clean_names(self.names))

    @property
    def is_empty(self) -> bool:
        return not self.names

    def describe(self) -> str:
        return f"{self.kind} " + ", ".join(self.names)

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "names": list(self.names)}

    @classmethod
    def from_fields(cls: type[_Names], fields: Mapping[str, Any]) -> _Names:
        return cls(read_str_list(fields, "names"))


@dataclass(frozen=True)
class NodeRule(NamesRule):
    """Matches records from any of ``names``: exact logger names or globs (case-sensitive).

    A name written as a ROS node name (``/ns/talker``) matches its logger name (``ns.talker``);
    one written ``ROBOT:NAME`` (``logger_levels.robot_qualified``) matches that robot's records only.
    """

    kind = "node"

    def compile(self, store: LogStore) -> SpanTest:
        anywhere: list[str] = []
        by_robot: dict[str, list[str]] = {}
        for name in self.names:
            robot, node = split_robot(name)
            (by_robot.setdefault(robot, []) if robot else anywhere).append(node)
        if not by_robot:
            lookup = IdLookup(store.nodes, _node_predicate(anywhere))
            return lambda chunk, lo, hi: lookup.mask(chunk.nodes, lo, hi)
        tests: list[tuple[IdLookup | None, IdLookup]] = []
        if anywhere:
            tests.append((None, IdLookup(store.nodes, _node_predicate(anywhere))))
        tests += [  # each robot's own nodes
            (IdLookup(store.robots, names_predicate([robot])), IdLookup(store.nodes, _node_predicate(nodes)))
            for robot, nodes in by_robot.items()
        ]

        def test(chunk: Chunk, lo: int, hi: int) -> bytes:
            mask = bytes(hi - lo)
            for robots, nodes in tests:
                found = nodes.mask(chunk.nodes, lo, hi)
                if robots is not None:
                    found = (
                        bytes(hi - lo) if chunk.robots is None else mask_and(found, robots.mask(chunk.robots, lo, hi))
                    )
                mask = mask_or(mask, found)
            return mask

        return test


def _node_predicate(names: Iterable[str]) -> Callable[[str], bool]:
    # A name as written too: ROS 1 loggers are node names (``/talker``).
    return names_predicate(form for n in names for form in (n, logger_name(n)))
