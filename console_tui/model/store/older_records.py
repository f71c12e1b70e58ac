"""Records older than those kept, placed before them; and one source's records taken out.

A log warehouse is read newest first (``sources.warehouse_source``): its older pages come
after the newer ones, and when its rows are read again (other rules) the old ones go.
Both are rewrites of the store (``LogStore.put_before``, ``rewrite_from``, whose
``rewind_listeners`` the view, the overview and the node counts follow); ``marked`` seqs (the
marks) are given so that only their moves are worked out. Older records put before the kept
ones cost what they are, not what the store holds (``put_before`` keeps the kept chunks whole).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from itertools import compress
from typing import Any, NamedTuple

from .late_records import Placed, add_in_time_order
from .log_store import LogStore
from .record_batch import RecordColumns


def add_older(store: LogStore, batch: RecordColumns, marked: Iterable[int] = ()) -> Placed | None:
    """Add ``batch``, records older than the store's (a page of history read backwards): all
    before the oldest kept when none is newer than it, else merged by stamp among them all.
    Returns where the kept records went (None when the store was empty or ``batch`` is)."""
    if not len(batch):
        return None
    order = batch.time_order()
    older = batch.reordered(order) if order is not None else batch
    if not len(store):
        store.extend(older)
        return None
    first, end = store.first_seq, store.end_seq
    if max(batch.stamps) > store.stamp_of(first):
        return add_in_time_order(store, batch, window=len(store), late_ns=0)
    shift = store.put_before(older)
    return Placed(first, {seq: seq + shift for seq in marked if first <= seq < end})


class Dropped(NamedTuple):
    """One source's records taken out: how many, where the others went, and the marked seqs
    that went with the dropped records."""

    dropped: int
    moved: dict[int, int]
    gone: list[int]


def drop_source(store: LogStore, source: str, marked: Iterable[int] = ()) -> Dropped:
    """Take every record whose ``source`` is ``source`` out of the store."""
    if source not in store.sources or not len(store):
        return Dropped(0, {}, [])
    ident = store.sources.id_of(source)
    first, end = store.first_seq, store.end_seq
    spans = list(store.spans(first, end))
    count = sum(span.chunk.sources[span.lo : span.hi].count(ident) for span in spans)
    if not count:
        return Dropped(0, {}, [])
    marks = [seq for seq in marked if first <= seq < end]
    if count == end - first:  # all of them: nothing is written again
        store.rewrite_from(first, RecordColumns([], [], [], [], [], [], [], []))
        return Dropped(count, {}, marks)
    keep = bytearray()
    for span in spans:
        keep += bytes(value != ident for value in span.chunk.sources[span.lo : span.hi])
    columns = store.columns(first, end)

    def kept(column: Sequence[Any]) -> list[Any]:
        return list(compress(column, keep))

    remaining = RecordColumns(
        kept(columns.stamps),
        kept(columns.levels),
        kept(columns.nodes),
        kept(columns.msgs),
        kept(columns.files),
        kept(columns.functions),
        kept(columns.lines),
        kept(columns.sources),
        None if columns.topics is None else kept(columns.topics),
        None if columns.robots is None else kept(columns.robots),
    )
    new_seq: dict[int, int] = {}
    at = first
    marked_set = set(marks)
    for offset, flag in enumerate(keep):
        if flag:
            if first + offset in marked_set:
                new_seq[first + offset] = at
            at += 1
    store.rewrite_from(first, remaining)
    gone = [seq for seq in marks if seq not in new_seq]
    return Dropped(count, new_seq, gone)
