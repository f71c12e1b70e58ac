"""Several files' records merged into one timeline, ordered by stamp."""

from __future__ import annotations

import heapq
import itertools
import time
from collections.abc import Iterable, Iterator, Sequence

from ...model.record import LogRecord

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
) -> Iterator[list[LogRecord]]:
    """Batches of every stream's records merged into one stamp order.

    Each stream is read lazily, only as far as the merge needs, so records start to
    come before any file is read to its end.
    """
    ordered = [sorted_by_stamp(stream, window) for stream in streams]
    merged = ordered[0] if len(ordered) == 1 else heapq.merge(*ordered, key=_stamp)
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


def _stamp(record: LogRecord) -> int:
    return record.stamp_ns
