"""Late records: a history that arrives after newer messages, placed by its stamp.

A live source's messages arrive about in time order, except its histories: a ROS 2 node's
``/rosout`` history (transient local) reaches a subscriber that joins late one publisher at
a time, and a fleet's robot that joins late sends its own after the other robots' newer
messages. Appended as they come they group the first rows by node, seconds apart.

``add_in_time_order`` appends a batch as the store always does (the hot path: a C-level
``min`` and ``max`` over its stamps more), unless its oldest record is more than ``LATE_NS``
older than the newest one kept. Then the batch and the store's newest records it belongs
among (at most ``WINDOW`` of them) are written again merged by stamp
(``LogStore.rewrite_from``; older records of the batch go first, in order, before that
window). A batch whose own records are that far apart (several publishers' histories in one
batch) is sorted before it is added. Delivery that is only a little out of order
(publishers' clocks, batching) stays as it came: rewriting for it would make the views count
again every moment. The caller decides when rows may move (``window`` 0: none do): only while
the table follows the tail.
"""

from __future__ import annotations

from typing import NamedTuple

from .intake_queue import Batch
from .record_batch import RecordColumns
from .store import LogStore

#: A batch is late when its oldest record is this much older than the newest kept one.
LATE_NS = 250_000_000
#: The most records of the store's tail a late batch is placed among.
WINDOW = 10_000


class Placed(NamedTuple):
    """A late batch written among the store's newest records: from seq ``start`` on, and
    where each record that was there before went (old seq -> new seq)."""

    start: int
    moved: dict[int, int]


def _span(batch: Batch) -> tuple[int, int] | None:
    """The oldest and the newest stamp of ``batch`` (None when it is empty)."""
    if not len(batch):
        return None
    stamps = batch.stamps if isinstance(batch, RecordColumns) else [record.stamp_ns for record in batch]
    return min(stamps), max(stamps)


def add_in_time_order(store: LogStore, batch: Batch, *, late_ns: int = LATE_NS, window: int = WINDOW) -> Placed | None:
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
    columns = batch if isinstance(batch, RecordColumns) else RecordColumns.from_records(batch)
    start = end
    floor = max(store.first_seq, end - window)
    while behind and start > floor and store.stamp_of(start - 1) > oldest:
        start -= 1
    merged = RecordColumns.joined([store.columns(start, end), columns]) if start < end else columns
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
