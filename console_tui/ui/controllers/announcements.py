"""What the console's controllers announce, and who listens: the intake says records were
taken in, the rules that they changed, the table that the store was cleared, the jumps that the marks
changed; whoever follows
them (the overview, the search, the rules' counts, the load bar, the status line) subscribes
where it is made, and the one announcing knows nobody.

A listener is called at once, in the order they subscribed, on the event loop. Announcements
are made once a batch of records or a tick, never once a record.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Generic, ParamSpec

from ...model.rules.ruleset import RuleSet

P = ParamSpec("P")


class Announcement(Generic[P]):
    """One kind of news, and its listeners."""

    __slots__ = ("_listeners",)

    def __init__(self) -> None:
        self._listeners: list[Callable[P, None]] = []

    def subscribe(self, listener: Callable[P, None]) -> None:
        self._listeners.append(listener)

    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> None:
        for listener in self._listeners:
            listener(*args, **kwargs)


@dataclass(frozen=True)
class TakenIn:
    """Records put into the store and the view."""

    #: How many.
    added: int
    #: A late history was placed by its stamps: the newest records are in another order.
    rewritten: bool = False


def _announcement() -> Announcement:
    return Announcement()


@dataclass(frozen=True)
class Announcements:
    """Every announcement of the console (``ConsoleContext.announce``)."""

    #: Records were added, while the table keeps its place (``LogTable.keeping_position``):
    #: what the rows are made of follows them here (the storms, the timeline).
    placing: Announcement[[]] = field(default_factory=_announcement)
    #: Records were taken in, the table in its place again: a batch (or a tick's batches).
    taken_in: Announcement[[TakenIn]] = field(default_factory=_announcement)
    #: An intake tick is over (15 a second, records or not).
    tick: Announcement[[]] = field(default_factory=_announcement)
    #: Other rules are in force (the rows shown change with them).
    rules_changed: Announcement[[RuleSet]] = field(default_factory=_announcement)
    #: Every record was dropped (``c``).
    cleared: Announcement[[]] = field(default_factory=_announcement)
    #: A mark was put on a row or taken off (the gutter shows them).
    marks_changed: Announcement[[]] = field(default_factory=_announcement)
