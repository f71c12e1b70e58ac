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
        if not batch:
            return
        with self._lock:
            self.received += len(batch)
            if self._waiting + len(batch) > self.limit:
                self.dropped += len(batch)
                return
            self._batches.append(batch)
            self._waiting += len(batch)

    def drain(self) -> list[LogRecord]:
        """Everything waiting, oldest first (an empty list when nothing is)."""
        with self._lock:
            if not self._batches:
                return []
            batches, self._batches = self._batches, deque()
            self._waiting = 0
        if len(batches) == 1:
            return batches[0]
        out: list[LogRecord] = []
        for batch in batches:
            out.extend(batch)
        return out

    def __len__(self) -> int:
        return self._waiting
