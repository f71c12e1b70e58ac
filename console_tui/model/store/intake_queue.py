"""The hand-off between a source's thread and the UI: batches of records, bounded."""

from __future__ import annotations

import threading
from collections import deque

from .indexed_chunk import IndexedChunk
from .record import LogRecord
from .record_batch import RecordColumns

DEFAULT_QUEUE_LIMIT = 2_000_000
#: A log file's chunk read by index (``IndexedChunk``: columns, no messages) counts as this
#: many of its records against a drain's ``limit``: what the UI's tick spends on it.
INDEXED_SHARE = 1 / 16

Batch = RecordColumns | IndexedChunk


class IntakeQueue:
    """A thread-safe queue of record batches (``RecordColumns``, or a file's ``IndexedChunk``s)
    that the UI drains on a timer.

    Sources ``put`` whole batches from their own threads; the UI calls ``drain_batches``
    (or ``drain``, for ``LogRecord``s) a few times a second and gets everything that
    arrived since, in order. Past ``limit`` records waiting, new batches are counted in
    ``dropped`` instead of kept, so a stalled UI cannot grow memory without bound and the
    loss is visible.
    """

    def __init__(self, limit: int = DEFAULT_QUEUE_LIMIT) -> None:
        self.limit = limit
        self._lock = threading.Lock()
        self._batches: deque[Batch] = deque()
        self._waiting = 0
        self.dropped = 0
        self.received = 0

    def put(self, batch: Batch) -> None:
        """Queue a batch; the caller hands it over and must not use it again."""
        size = len(batch)
        if not size:
            return
        with self._lock:
            self.received += size
            if self._waiting + size > self.limit:
                self.dropped += size
                return
            self._batches.append(batch)
            self._waiting += size

    def drain_batches(self, limit: int | None = None) -> list[Batch]:
        """What is waiting, oldest first, as the batches that were put (the last one cut
        to fit; a chunk read by index is never cut), at most ``limit`` records in all (a
        chunk read by index counting ``INDEXED_SHARE`` of its records)."""
        out: list[Batch] = []
        taken = spent = 0.0
        with self._lock:
            batches = self._batches
            while batches and (limit is None or spent < limit):
                batch = batches.popleft()
                size = len(batch)
                if isinstance(batch, IndexedChunk):
                    spent += size * INDEXED_SHARE
                elif limit is not None and size > limit - spent:
                    room = int(limit - spent)
                    batch, rest = batch.slice(0, room), batch.slice(room, size)
                    batches.appendleft(rest)
                    size = room
                    spent += size
                else:
                    spent += size
                out.append(batch)
                taken += size
            self._waiting -= int(taken)
        return out

    def drain_columns(self, limit: int | None = None) -> list[RecordColumns]:
        """``drain_batches`` of a queue of live records (no chunk read by index goes there)."""
        return [batch for batch in self.drain_batches(limit) if isinstance(batch, RecordColumns)]

    def drain(self, limit: int | None = None) -> list[LogRecord]:
        """What is waiting, oldest first, as records, at most ``limit`` (an empty list if none)."""
        out: list[LogRecord] = []
        for batch in self.drain_batches(limit):
            out.extend((batch.with_messages() if isinstance(batch, IndexedChunk) else batch).records())
        return out

    def __len__(self) -> int:
        return self._waiting
