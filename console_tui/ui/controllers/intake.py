"""The intake: the sources started and stopped, and what they queued taken into the store.

Sources (the live stream, file loads) run in threads or processes of their own and put records
on an ``IntakeQueue``; each tick (``DRAIN_INTERVAL``) moves what is there into the store and
the view, at most ``MAX_RECORDS_PER_TICK`` at a time, of them at most
``MAX_LIVE_RECORDS_PER_TICK`` live ones, and announces them (``announcements``): what follows
them (the overview, the search, the rules' counts, the load bar) subscribes there.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Sequence
from typing import Any, Protocol

from ...model.store.indexed_chunk import IndexedChunk
from ...model.store.intake_queue import Batch, IntakeQueue
from ...model.store.late_records import WINDOW, HistoryWindow, Placed, add_in_time_order
from ...model.store.record import LogRecord
from ...model.store.record_batch import RecordColumns
from ...ros.fleet import Robot
from ...sources.status import SourceStatus
from .announcements import TakenIn
from .context import ConsoleContext

DRAIN_INTERVAL = 1 / 15
#: Records taken into the store per tick at most, so one tick never stalls the screen.
MAX_RECORDS_PER_TICK = 20_000
#: Live records per tick at most: 120,000 a second, twice what a live intake takes at most,
#: so a backlog (after the loop was held up) still goes at once; but a tick that takes one in
#: costs at most about 20 ms of CPU (2.5 µs a record at 50,000/s with the store full), where
#: 20,000 cost 50 and held keys up for as long.
MAX_LIVE_RECORDS_PER_TICK = 8_000
RATE_WINDOW_S = 2.0
#: How long quitting waits for the sources to stop, at most.
SOURCE_STOP_TIMEOUT_S = 2.0


class Source(Protocol):
    """A producer of records (the live stream, a file loader) the app starts and stops."""

    status: SourceStatus

    def start(self) -> None: ...

    def stop(self) -> None: ...


def _stop_quietly(source: Source) -> None:
    try:
        source.stop()
    except Exception:
        pass


class IntakeController:
    """Sources in, records into the store each tick, sources out when the app ends."""

    def __init__(
        self,
        context: ConsoleContext,
        *,
        sources: list[Source],
        queue: IntakeQueue,
        file_queue: IntakeQueue,
        files_loading: Callable[[], bool],
        robots: Sequence[Robot],
    ) -> None:
        c = context
        self._host, self._store, self._view, self._table, self._marks = c.host, c.store, c.view, c.table, c.marks
        self._clock, self._changed, self._announce = c.clock, c.changed, c.announce
        #: The sources running (emptied when they are stopped).
        self.sources = sources
        #: The live sources' records; file loads have a queue of their own, taken in first.
        self._queue = queue
        self._file_queue = file_queue
        #: Files are being read: live records wait meanwhile, so that the rows stay in time order.
        self._files_loading = files_loading
        #: A fleet's robots (``--domain``, ``--master``, ``--fleet``), or none.
        self._robots = robots
        self._rate = 0.0
        self._rate_at = 0.0
        #: When records arrived, and how many: the receive rate.
        self._arrivals: deque[tuple[float, int]] = deque()
        #: The threads stopping the sources, once quitting began.
        self._stopping: list[threading.Thread] = []
        #: The slower intake path was said (``tell_slow_intake``).
        self._slow_intake_told = False
        #: When live histories are due, to be placed by their stamps (on the app's clock).
        self.histories = HistoryWindow(c.clock)

    # -- the sources ------------------------------------------------------------------------------

    def start_sources(self) -> None:
        """Start the sources. (The logger control starts when the logger levels pane first
        opens: ``LoggerPane.when_opened``.)"""
        for source in self.sources:
            self._start(source)

    def _start(self, source: Any) -> None:
        try:
            source.start()
        except Exception as error:
            self._host.notify(f"Could not start {type(source).__name__}: {error}", severity="error", timeout=10)

    def begin_stopping_sources(self) -> None:
        """Start stopping every source, all at once, each in a thread of its own: each may
        wait a moment for a process of its own (the intake process, demo nodes) to end, and
        that runs while Textual takes the screens down, not after."""
        sources = list(self.sources)
        self.sources.clear()
        for source in sources:
            thread = threading.Thread(target=_stop_quietly, args=(source,), name="console-tui-stop", daemon=True)
            thread.start()
            self._stopping.append(thread)

    def stop_sources(self) -> None:
        """Stop every source (``begin_stopping_sources``) and wait until they have stopped
        (``SOURCE_STOP_TIMEOUT_S`` at most): the app should be gone within a second of ``q``."""
        self.begin_stopping_sources()
        deadline = time.monotonic() + SOURCE_STOP_TIMEOUT_S
        for thread in self._stopping:
            thread.join(max(deadline - time.monotonic(), 0.0))

    # -- records ----------------------------------------------------------------------------------

    def drain_intake(self) -> None:
        """Move what the sources queued into the store, in one batch per tick.

        Records from files come first; live records wait while files load, so that a
        view of files plus the live stream stays in time order. A fleet's live records of
        one tick are merged by stamp (each robot's intake process sends its own batches);
        a late history among them (``late_records``) is placed by its stamp while the table
        follows the tail, in the moments histories are due (``HistoryWindow``)."""
        batches = self._file_queue.drain_batches(MAX_RECORDS_PER_TICK)
        for source in self.sources:
            status = source.status
            self.histories.note(id(source), status.publishers, status.topic)
        if not self._files_loading():
            room = min(MAX_RECORDS_PER_TICK - sum(map(len, batches)), MAX_LIVE_RECORDS_PER_TICK)
            live: list[RecordColumns] = self._queue.drain_columns(room)
            if len(live) > 1 and len(self._robots) > 1:  # a fleet: what its robots sent meanwhile, by time
                live = [RecordColumns.in_time_order(live)]
        else:
            live = []
        if batches or live:
            self.add_batches([*batches, *live], live_from=len(batches))
        self.tell_slow_intake()
        self._announce.tick()
        self._changed()

    def tell_slow_intake(self) -> None:
        """The first time a live source takes the slower path (no take loop in C), say so
        once, with what it costs (the summary, S, keeps saying it)."""
        if self._slow_intake_told:
            return
        for source in self.sources:
            text = source.status.slow_path_text()
            if text:
                self._slow_intake_told = True
                self._host.notify(text[0].upper() + text[1:], severity="warning", timeout=15, markup=False)
                return

    def add_records(self, records: Iterable[LogRecord]) -> None:
        """Put records made one by one into the store and the view (tests, demos)."""
        self.add_batches([RecordColumns.from_records(list(records))])

    def add_batches(self, batches: Sequence[Batch], *, live_from: int | None = None) -> int:
        """Put batches into the store and the view; how many.
        Batches from ``live_from`` on are live: one that is late is sorted, and while the table
        follows the tail (nobody reads rows that would move) placed among the newest rows by its
        stamps. What follows the records hears of them (``Announcements``): ``placing`` while the
        table keeps its place, ``taken_in`` after."""
        table = self._table
        first_live = len(batches) if live_from is None else live_from
        # Rows on the screen stay put; and only histories are placed, not clocks that differ.
        following = table.following and table.paused_end is None
        window = WINDOW if following and self.histories.due() else 0
        added = 0
        rewritten = False
        with table.keeping_position():
            for index, batch in enumerate(batches):
                if isinstance(batch, IndexedChunk):
                    added += len(self._store.extend_indexed(batch))
                elif index >= first_live:
                    placed = add_in_time_order(self._store, batch, window=window)
                    added += len(batch)
                    if placed is not None:
                        self._marks.move(placed.moved)
                        rewritten = True
                else:
                    added += len(self._store.extend(batch))
            self._view.update()
            self._announce.placing()
        self._arrivals.append((self._clock(), added))
        self._announce.taken_in(TakenIn(added, rewritten))
        return added

    def add_placed(self, place: Callable[[], Placed | None]) -> None:
        """Records put into the store by ``place`` where they belong, which may write it
        again (a log warehouse's older rows, a source's rows taken out): announced as
        ``add_batches`` announces a late history, the rows on the screen kept in place."""
        before = len(self._store)
        with self._table.keeping_position():
            placed = place()
            if placed is not None:
                self._marks.move(placed.moved)
            self._view.update()
            self._announce.placing()
        # (History put in place, not arrivals: the receive rate leaves them out.)
        self._announce.taken_in(TakenIn(max(len(self._store) - before, 0), placed is not None))

    def receive_rate(self) -> float:
        """Records a second over the last ``RATE_WINDOW_S``, recomputed once a second
        (so the status line is not redrawn every tick for a changing digit)."""
        now = self._clock()
        if now - self._rate_at < 1.0:
            return self._rate
        arrivals = self._arrivals
        while arrivals and arrivals[0][0] < now - RATE_WINDOW_S:
            arrivals.popleft()
        self._rate = sum(count for _, count in arrivals) / RATE_WINDOW_S
        self._rate_at = now
        return self._rate
