"""The hand-off between a source's thread and the UI: batches of records, bounded."""

from __future__ import annotations

import threading
from collections import deque

from .record import LogRecord
from .record_batch import RecordColumns

DEFAULT_QUEUE_LIMIT = 2_000_000


class IntakeQueue:
    """A thread-safe queue of record batches (``RecordColumns``) that the UI drains on a timer.

    Sources ``put`` whole batches from their own threads; the UI calls ``drain_batches``
    (or ``drain``, for ``LogRecord``s) a few times a second and gets everything that
    arrived since, in order. Past ``limit`` records waiting, new batches are counted in
    ``dropped`` instead of kept, so a stalled UI cannot grow memory without bound and the
    loss is visible.
    """

    def __init__(self, limit: int = DEFAULT_QUEUE_LIMIT) -> None:
        self.limit = limit
        self._lock = threading.Lock()
        self._batches: deque[RecordColumns] = deque()
        self._waiting = 0
        self.dropped = 0
        self.received = 0

    def put(self, batch: RecordColumns) -> None:
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

    def drain_batches(self, limit: int | None = None) -> list[RecordColumns]:
        """What is waiting, oldest first, as the batches that were put (the last one cut
        to fit), at most ``limit`` records in all."""
        out: list[RecordColumns] = []
        taken = 0
        with self._lock:
            batches = self._batches
            while batches and (limit is None or taken < limit):
                batch = batches.popleft()
                size = len(batch)
                if limit is not None and size > limit - taken:
                    room = limit - taken
                    batch, rest = batch.slice(0, room), batch.slice(room, size)
                    batches.appendleft(rest)
                    size = room
                out.append(batch)
                taken += size
            self._waiting -= taken
        return out

    def drain(self, limit: int | None = None) -> list[LogRecord]:
        """What is waiting, oldest first, as records, at most ``limit`` (an empty list if none)."""
        out: list[LogRecord] = []
        for batch in self.drain_batches(limit):
            out.extend(batch.records())
        return out

    def __len__(self) -> int:
        return self._waiting
