"""When Python's cyclic garbage collector may run, so that it never stalls the screen.

Measured with 10k messages/s arriving (benchmarks/screen.py): with Python's default
thresholds, full (oldest-generation) collections ran twice a second and took 75-130 ms
each, because records waiting a tick in the intake queue and Textual's per-frame objects
survive long enough to be promoted. Here the objects made at start-up are frozen out of
collections, young collections stay as they are (a few ms), and full collections are run
by the app itself: when nothing has arrived for a while, or at the latest every
``FULL_COLLECTION_MAX_INTERVAL_S``.
"""

from __future__ import annotations

import gc
import time

NO_AUTOMATIC_FULL_COLLECTIONS = 1_000_000_000
QUIET_BEFORE_COLLECTING_S = 2.0
FULL_COLLECTION_MIN_INTERVAL_S = 30.0
FULL_COLLECTION_MAX_INTERVAL_S = 600.0


class CollectionPolicy:
    """Call ``start`` once the app is up and ``tick`` on every drain of the intake."""

    def __init__(self, clock=time.monotonic) -> None:
        self.clock = clock
        self.last_full = clock()
        self.last_arrival = clock()
        self.full_collections = 0

    def start(self) -> None:
        gc.freeze()
        young, middle, _ = gc.get_threshold()
        gc.set_threshold(young, middle, NO_AUTOMATIC_FULL_COLLECTIONS)

    def tick(self, arrived: int) -> None:
        now = self.clock()
        if arrived:
            self.last_arrival = now
        since_full = now - self.last_full
        quiet = now - self.last_arrival >= QUIET_BEFORE_COLLECTING_S
        if (quiet and since_full >= FULL_COLLECTION_MIN_INTERVAL_S) or since_full >= FULL_COLLECTION_MAX_INTERVAL_S:
            gc.collect()
            self.last_full = self.clock()
            self.full_collections += 1
