"""Several files' records merged into one timeline, ordered by stamp."""

from __future__ import annotations

import collections
import heapq
import itertools
import time
from collections.abc import Iterable, Iterator, Sequence

from ...model.store.record import LogRecord

#: Records held back per file to put slightly out-of-order stamps right.
REORDER_WINDOW = 10_000
BATCH = 5_000
#: A batch goes out after this long even when not full, so a view fills steadily.
MAX_BATCH_DELAY_S = 0.1


def sorted_by_stamp(batches: Iterable[list[LogRecord]], window: int = REORDER_WINDOW) -> Iterator[LogRecord]:
    """The records in stamp order, as far as a window of ``window`` records can sort them.

    Files are nearly in time order already (a node's threads and several publishers
    interleave a little); a record more than ``window`` places out of order comes
    out late rather than holding everything back. Equal stamps keep their file order.
    """
    heap: list[tuple[int, int, LogRecord]] = []
    counter = itertools.count()
    push, pushpop, pop = heapq.heappush, heapq.heappushpop, heapq.heappop
    for batch in batches:
        for record in batch:
            entry = (record.stamp_ns, next(counter), record)
            if len(heap) < window:
                push(heap, entry)
            else:
                yield pushpop(heap, entry)[2]
    while heap:
        yield pop(heap)[2]


def merge_by_time(
    streams: Sequence[Iterable[list[LogRecord]]],
    *,
    batch_size: int = BATCH,
    window: int = REORDER_WINDOW,
    starts: Sequence[int | None] | None = None,
) -> Iterator[list[LogRecord]]:
    """Batches of every stream's records merged into one stamp order.

    Each stream is read lazily, only as far as the merge needs, so records start to
    come before any file is read to its end. ``starts`` (one per stream, None where
    unknown) says about when each stream's records begin: such a stream is not touched
    (its file not even opened) until the merge reaches that time.
    """
    ordered = [sorted_by_stamp(stream, window) for stream in streams]
    if len(ordered) == 1:
        merged: Iterable[LogRecord] = ordered[0]
    elif starts is None:
        merged = heapq.merge(*ordered, key=_stamp)
    else:
        merged = _merge_when_due(ordered, starts)
    batch: list[LogRecord] = []
    deadline = time.monotonic() + MAX_BATCH_DELAY_S
    for record in merged:
        batch.append(record)
        if len(batch) >= batch_size or (len(batch) % 256 == 0 and time.monotonic() >= deadline):
            yield batch
            batch = []
            deadline = time.monotonic() + MAX_BATCH_DELAY_S
    if batch:
        yield batch


def _merge_when_due(streams: list[Iterator[LogRecord]], starts: Sequence[int | None]) -> Iterator[LogRecord]:
    """Records of ``streams`` in stamp order, each stream started when the merge reaches
    its start (those without one at once). Equal stamps keep the streams' order."""
    due = collections.deque(sorted(range(len(streams)), key=lambda i: (starts[i] is not None, starts[i] or 0, i)))
    heap: list[tuple[int, int, LogRecord]] = []
    while True:
        while due and (not heap or (start := starts[due[0]]) is None or start <= heap[0][0]):
            index = due.popleft()
            first = next(streams[index], None)
            if first is not None:
                heapq.heappush(heap, (first.stamp_ns, index, first))
        if not heap:
            return
        _, index, record = heap[0]
        yield record
        following = next(streams[index], None)
        if following is None:
            heapq.heappop(heap)
        else:
            heapq.heapreplace(heap, (following.stamp_ns, index, following))


def _stamp(record: LogRecord) -> int:
    return record.stamp_ns
