"""Late records: a history that arrives after newer messages, placed by its stamp.

``add_in_time_order`` appends a batch as the store always does, unless its oldest record is more
than ``LATE_NS`` older than the newest one kept. Then the batch and the store's newest records it
belongs among (at most ``WINDOW`` of them) are written again merged by stamp
(``LogStore.rewrite_from``; older records of the batch go first, in order, before that window). A
batch whose own records are that far apart (several publishers' histories in one batch) is
sorted before it is added. The caller decides when rows may move (``window`` 0: none do): only
while the table follows the tail, and only while histories are due (``HistoryWindow``: for a few
seconds after a source starts, a publisher joins it or it changes topic). Why, and what it
costs: docs/decisions/0009-late-histories-rewrite-tail.md.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Hashable
from typing import NamedTuple

from .log_store import LogStore
from .record_batch import RecordColumns

#: A batch is late when its oldest record is this much older than the newest kept one.
LATE_NS = 250_000_000
#: The most records of the store's tail a late batch is placed among.
WINDOW = 10_000
#: How long after a source starts, a publisher joins it or it changes topic its histories
#: may still arrive (a transient-local history comes as the subscription matches).
HISTORY_S = 3.0


class HistoryWindow:
    """Whether late histories are due now: ``note`` each source's state every tick (a key
    per source, its publisher count and topic); ``due`` says whether one started, gained a
    publisher or changed topic within ``seconds``."""

    def __init__(self, clock: Callable[[], float] = time.monotonic, seconds: float = HISTORY_S) -> None:
        self.clock = clock
        self.seconds = seconds
        self._states: dict[Hashable, tuple[int, str]] = {}
        self._until = float("-inf")

    def note(self, source: Hashable, publishers: int, topic: str) -> None:
        before = self._states.get(source)
        if before is None or publishers > before[0] or topic != before[1]:
            self._until = self.clock() + self.seconds
        self._states[source] = (publishers, topic)

    def due(self) -> bool:
        return self.clock() < self._until


class Placed(NamedTuple):
    """A late batch written among the store's newest records: from seq ``start`` on, and
    where each record that was there before went (old seq -> new seq)."""

    start: int
    moved: dict[int, int]


def _span(batch: RecordColumns) -> tuple[int, int] | None:
    """The oldest and the newest stamp of ``batch`` (None when it is empty)."""
    if not len(batch):
        return None
    return min(batch.stamps), max(batch.stamps)


def add_in_time_order(
    store: LogStore, batch: RecordColumns, *, late_ns: int = LATE_NS, window: int = WINDOW
) -> Placed | None:
    """Add ``batch`` to ``store``, in time order when it is late: placed by stamp among the
    newest ``window`` records (returns where), or, with ``window`` 0 or when only the
    batch itself is out of order, sorted among itself (returns None)."""
    span = _span(batch)
    end = store.end_seq
    behind = span is not None and len(store) > 0 and span[0] < store.stamp_of(end - 1) - late_ns
    if span is None or (not behind and span[0] >= span[1] - late_ns):
        store.extend(batch)
        return None
    oldest = span[0]
    start = end
    floor = max(store.first_seq, end - window)
    while behind and start > floor and store.stamp_of(start - 1) > oldest:
        start -= 1
    merged = RecordColumns.joined([store.columns(start, end), batch]) if start < end else batch
    order = merged.time_order()
    if order is None:
        store.extend(batch)
        return None
    if start == end:
        store.extend(merged.reordered(order))
        return None
    store.rewrite_from(start, merged.reordered(order))
    kept = end - start
    moved = {start + old: start + new for new, old in enumerate(order) if old < kept and old != new}
    return Placed(start, moved)
