"""When Python's cyclic garbage collector runs, so that it stays short and memory stays flat.

Young collections stay automatic. The oldest generation is collected only here, every
``FULL_COLLECTION_PERIOD_S``, in a turn of the event loop of its own ``delay`` after a drain
of the intake (half way to the next): not in the drain's turn, nor just before the frame the
drain asks for, where it would lengthen the longest pause by its own length. What start-up
made is frozen out of collections (``gc.freeze``), so a full collection visits only what the
app made since: mostly Textual's strips and their caches, and the cycles of widgets removed
and screens closed. Why collections are scheduled this way, and what was measured:
docs/decisions/0017-garbage-collection-schedule.md.
"""

from __future__ import annotations

import asyncio
import gc
import time
from collections.abc import Callable

NO_AUTOMATIC_FULL_COLLECTIONS = 1_000_000_000
FULL_COLLECTION_PERIOD_S = 2.0
#: Until this long after start-up, each full collection freezes what survived it (see ``CollectionPolicy``).
SETTLED_S = 10.0


class CollectionPolicy:
    """Call ``start`` once the app has drawn its first frame and ``tick`` on every drain of the intake.

    ``start`` freezes what exists then; each full collection until ``settled`` seconds
    later (that one included) freezes what is still alive once more: what the app makes while
    it starts after its first frame (rclpy and the modules the logger pane and the live source
    import in their threads, the first screens' caches). Freezing at each of them, not only at
    the last, keeps the collections of the first seconds short too. ``refrozen`` says start-up
    has settled (no more freezing). An object frozen lives on until nothing refers to it; only
    a cycle among frozen objects would wait for ever, and these are made once.
    """

    def __init__(
        self,
        clock: Callable[[], float] = time.monotonic,
        period: float = FULL_COLLECTION_PERIOD_S,
        delay: float = 0.03,
        settled: float = SETTLED_S,
    ) -> None:
        self.clock = clock
        self.period = period
        self.delay = delay
        self.settled = settled
        self.started: float | None = None
        self.refrozen = False
        self._scheduled = False
        self.last_full = clock()
        self.full_collections = 0
        #: The longest full collection so far, in seconds (for benchmarks), and the CPU this
        #: thread spent in it (less than ``longest`` when the thread was made to wait).
        self.longest = 0.0
        self.longest_cpu = 0.0

    def start(self) -> None:
        """Freeze what exists and turn the collector on: start-up runs without it (``cli.main``),
        and this comes after the first frame. Nothing is collected first: a collection of all
        that start-up made (100,000 objects, none ever collected, so none untracked) took
        0.1-0.2 s, a stall just after the first frame, for the 7,000 objects (1 MB) of garbage
        start-up leaves, which stay frozen."""
        gc.freeze()
        young, middle, _ = gc.get_threshold()
        gc.set_threshold(young, middle, NO_AUTOMATIC_FULL_COLLECTIONS)
        gc.enable()
        self.last_full = self.started = self.clock()

    def tick(self) -> None:
        """Once ``period`` has passed, schedule a full collection ``delay`` from now (at
        once when no event loop runs)."""
        if self._scheduled or self.clock() - self.last_full < self.period:
            return
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            self.collect()
            return
        self._scheduled = True
        loop.call_later(self.delay, self.collect)

    def collect(self) -> None:
        self._scheduled = False
        began, began_cpu = time.perf_counter(), time.thread_time()
        gc.collect()
        took = time.perf_counter() - began
        if took > self.longest:
            self.longest, self.longest_cpu = took, time.thread_time() - began_cpu
        self.last_full = self.clock()
        self.full_collections += 1
        if not self.refrozen and self.started is not None:
            # Start-up is still making objects that live for good: set aside what survived.
            self.refrozen = self.last_full - self.started >= self.settled
            gc.freeze()
