"""The hand-off between a source's thread and the UI: batches of records, bounded."""

from __future__ import annotations

import threading
from collections import deque

from .record import LogRecord

DEFAULT_QUEUE_LIMIT = 2_000_000


class IntakeQueue:
    """A thread-safe queue of record batches that the UI drains on a timer.

    Sources ``put`` whole batches from their own threads; the UI calls ``drain`` a few
    times a second and gets everything that arrived since, in order. Past ``limit``
    records waiting, new batches are counted in ``dropped`` instead of kept, so a stalled
    UI cannot grow memory without bound and the loss is visible.
    """

    def __init__(self, limit: int = DEFAULT_QUEUE_LIMIT) -> None:
        self.limit = limit
        self._lock = threading.Lock()
        self._batches: deque[list[LogRecord]] = deque()
        self._waiting = 0
        self.dropped = 0
        self.received = 0

    def put(self, batch: list[LogRecord]) -> None:
        """Queue a batch; the caller hands it over and must not use it again."""
        if not batch:
            return
        with self._lock:
            self.received += len(batch)
            if self._waiting + len(batch) > self.limit:
                self.dropped += len(batch)
                return
            self._batches.append(batch)
            self._waiting += len(batch)

    def drain(self, limit: int | None = None) -> list[LogRecord]:
        """What is waiting, oldest first, at most ``limit`` records (an empty list if none)."""
        out: list[LogRecord] = []
        with self._lock:
            batches = self._batches
            while batches and (limit is None or len(out) < limit):
                batch = batches.popleft()
                room = len(batch) if limit is None else limit - len(out)
                if len(batch) > room:
                    batches.appendleft(batch[room:])
                    batch = batch[:room]
                if out:
                    out.extend(batch)
                else:
                    out = batch  # handed over by the producer: ours to extend
                self._waiting -= len(batch)
        return out

    def __len__(self) -> int:
        return self._waiting
