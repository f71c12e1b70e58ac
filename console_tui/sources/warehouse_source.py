"""The log warehouse as a source of the console: ``otel_logs`` read in a thread of its own.

``WarehouseSource`` asks the table for the newest rows of its window (``--since``/``--until``
and the rules' SQL, ``warehouse.pushdown``) and hands them over as ``Delivery``s, which the
app takes on its own clock (``take``), a small first page and then, a moment later
(``prefetch_after_s``), older ones up to ``prefetch_rows``; then, while it follows, the newer
rows every ``poll_s``, and older ones when asked (``ask_older``: the person scrolled past the
oldest row). New rules (``ask``) that change what SQL can leave out start a new generation: the app
drops the rows of the old one and takes the new one's. Nothing here waits for the app, and
the app never waits for the warehouse: a slow or absent warehouse shows in ``status`` (what it
is doing, for how long, what went wrong), and is asked again after a pause that grows to
``MAX_RETRY_S``. ``WindowReader`` reads a window forward for ``tail`` and ``convert``.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass

from ..model.rules.ruleset import RuleSet
from ..model.store.record_batch import RecordColumns
from ..warehouse.address import Address
from ..warehouse.clickhouse import TableClient, WarehouseError
from ..warehouse.pages import Abandoned, TablePages
from ..warehouse.pushdown import where, window_sql
from .status import SourceStatus

#: Rows of the first page: the first screen, and what a rule change shows at once (a tall
#: terminal's screenful: few, so that they are found in the table's newest part; the rest
#: comes at once after, ``PREFETCH_ROWS``).
FIRST_ROWS = 250
#: Rows read after the first page without being asked (older pages, placed before it).
PREFETCH_ROWS = 50_000
#: Prefetched a piece at a time, each a few short queries (new rules wait for the one
#: running: the rest of a piece is given up, ``pages.Abandoned``): the first of
#: ``PREFETCH_PIECE`` rows, then twice as many after a piece read within ``PIECE_BUDGET_S``
#: and half as many after one that took longer (the rules keep few rows: each is found far
#: back), from ``MIN_PREFETCH_PIECE`` to ``MAX_PREFETCH_PIECE``.
PREFETCH_PIECE = 1_000
MIN_PREFETCH_PIECE = 500
MAX_PREFETCH_PIECE = 10_000
PIECE_BUDGET_S = 0.5
#: Prefetching starts this long after a first page: rules changed again meanwhile (a person
#: typing one query after another) are not held up behind a prefetch's query.
PREFETCH_AFTER_S = 1.0
#: Rows of each older page, and of each poll while following.
PAGE_ROWS = 50_000
POLL_S = 2.0
#: A query running this long is said on the status line.
SLOW_S = 1.5
RETRY_S = 1.0
MAX_RETRY_S = 30.0

NEWEST, NEWER, OLDER = "newest", "newer", "older"


@dataclass(frozen=True)
class Delivery:
    """Rows for the app: the first page of ``generation`` (``newest``: what came before goes),
    or the newer or older ones after it."""

    generation: int
    kind: str
    columns: RecordColumns


def next_piece(piece: int, seconds: float) -> int:
    """The rows of the prefetch's next piece, after one of ``piece`` rows read in ``seconds``."""
    if seconds <= PIECE_BUDGET_S:
        return min(piece * 2, MAX_PREFETCH_PIECE)
    return max(piece // 2, MIN_PREFETCH_PIECE)


def window_condition(since_ns: int | None, until_ns: int | None, rules: RuleSet | None) -> str:
    """The SQL of a window and the rules that go down into it."""
    parts = [window_sql(since_ns, until_ns), where(rules or RuleSet())]
    kept = [part for part in parts if part != "1"]
    return " AND ".join(f"({part})" for part in kept) or "1"


class WarehouseSource:
    """Reads ``address``'s table into deliveries (see the module's text)."""

    def __init__(
        self,
        address: Address,
        *,
        since_ns: int | None = None,
        until_ns: int | None = None,
        rules: RuleSet | None = None,
        max_rows: int = 1_000_000,
        first_rows: int = FIRST_ROWS,
        page_rows: int = PAGE_ROWS,
        prefetch_rows: int = PREFETCH_ROWS,
        follow: bool = True,
        poll_s: float = POLL_S,
        prefetch_after_s: float = PREFETCH_AFTER_S,
        client: Callable[[Address], TableClient] = TableClient,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.address = address
        self.since_ns, self.until_ns = since_ns, until_ns
        self.max_rows = max_rows
        self.first_rows = min(first_rows, max_rows)
        self.page_rows = page_rows
        self.prefetch_rows = min(prefetch_rows, max_rows)
        #: Following: the newer rows are asked for (not with ``--until``).
        self.follow = follow and until_ns is None
        self.poll_s = poll_s
        self.prefetch_after_s = prefetch_after_s
        #: When the first page of the generation shown was read (``_clock``).
        self._newest_at = 0.0
        self._connect = client
        self._clock = clock
        self.name = address.text
        self._lock = threading.Lock()
        self._wake = threading.Event()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._deliveries: list[Delivery] = []
        self._condition = window_condition(since_ns, until_ns, rules)
        self._window = window_condition(since_ns, until_ns, None)
        self.generation = 0
        self._asked_generation = 1
        self._older_asked = False
        self._piece = PREFETCH_PIECE
        #: What the thread is doing, since when (``_clock``), and what went wrong last.
        self._doing = "starting"
        self._since = clock()
        self._problem = ""
        self.loaded = 0
        self.at_start = False
        self.repaired = 0
        self.duplicates = 0
        self._running = False

    # -- from the app ----------------------------------------------------------------------------

    def start(self) -> None:
        if self._thread is None:
            self._running = True
            self._thread = threading.Thread(target=self._run, name="console-tui-warehouse", daemon=True)
            self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._wake.set()
        if self._thread is not None:
            self._thread.join(2.0)

    def ask(self, rules: RuleSet) -> bool:
        """Put ``rules`` in force: when what SQL can leave out changes, read the window again
        (a new generation); whether it does."""
        condition = window_condition(self.since_ns, self.until_ns, rules)
        with self._lock:
            if condition == self._condition:
                return False
            self._condition = condition
            self._asked_generation += 1
            self._deliveries = []
        self._wake.set()
        return True

    def ask_older(self) -> bool:
        """Ask for the page before the oldest row read; False when there is none to ask for."""
        if self.at_start or self.loaded >= self.max_rows:
            return False
        self._older_asked = True
        self._wake.set()
        return True

    def take(self) -> list[Delivery]:
        """What has come since the last call (of the generation asked for last)."""
        with self._lock:
            taken, self._deliveries = self._deliveries, []
            return [d for d in taken if d.generation == self._asked_generation]

    @property
    def status(self) -> SourceStatus:
        """What the warehouse is doing, for the status line (made at each call)."""
        doing, since, problem = self._doing, self._since, self._problem
        seconds = self._clock() - since
        slow = ""
        if doing.startswith("asking") and seconds >= SLOW_S:  # said where the line keeps it
            slow = doing = f"{doing}: {seconds:.0f} s so far"
        path = f"{self.loaded:,} rows read"
        if doing:
            path += f", {doing}"
        elif self.follow:
            path += ", following"
        if not self.generation:
            empty = f"asking the log warehouse {self.name}…"
        else:
            empty = f"no rows in {self.name} in this window" + (
                " under these rules" if self._condition != self._window else ""
            )
        return SourceStatus(
            topic="",
            publishers=1 if self.generation else 0,
            origin=self.address.short_text(),
            remark=slow,
            path=path,
            problem=problem,
            running=self._running,
            hint=empty,
            path_is_progress=True,
        )

    # -- the thread ------------------------------------------------------------------------------

    def _set(self, doing: str, problem: str | None = None) -> None:
        self._doing, self._since = doing, self._clock()
        if problem is not None:
            self._problem = problem

    def _deliver(self, generation: int, kind: str, columns: RecordColumns) -> None:
        with self._lock:
            if generation == self._asked_generation:
                self._deliveries.append(Delivery(generation, kind, columns))

    def _prefetch_due(self, pages: TablePages) -> float | None:
        """Seconds until the next prefetch (0: now), or None: nothing is left to prefetch."""
        if self.loaded >= self.prefetch_rows or pages.at_start:
            return None
        return max(self._newest_at + self.prefetch_after_s - self._clock(), 0.0)

    def _read(self, client: TableClient, pages: TablePages | None) -> TablePages:
        """One query's worth: the first page of the generation asked for, or an older page
        (asked for, or prefetched), or the newer rows; the pages of the generation read. (A
        method of its own: the page read is not held while the thread waits.)"""
        with self._lock:
            generation, condition = self._asked_generation, self._condition
        if pages is None or generation != self.generation:
            self._set("asking the log warehouse")
            pages = TablePages(
                client, condition, source=self.name, abandoned=lambda: self._asked_generation != generation
            )
            page = pages.newest(self.first_rows)
            self.generation, self.loaded, self._older_asked = generation, len(page), False
            self._piece = PREFETCH_PIECE
            self._newest_at = self._clock()
            self._deliver(generation, NEWEST, page)
        elif self._older_asked or self._prefetch_due(pages) == 0:
            asked, self._older_asked = self._older_asked, False
            room = self.max_rows - self.loaded
            if room > 0 and not pages.at_start:
                self._set("asking for older rows")
                size = self.page_rows if asked else min(self.prefetch_rows - self.loaded, self._piece)
                began = self._clock()
                page = pages.older(min(size, room))
                if not asked:
                    self._piece = next_piece(self._piece, self._clock() - began)
                self.loaded += len(page)
                self._deliver(generation, OLDER, page)
        elif self.follow:
            self._set("asking for newer rows")
            page = pages.newer(self.page_rows)
            self.loaded += len(page)
            if len(page):
                self._deliver(generation, NEWER, page)
        return pages

    def _run(self) -> None:
        client: TableClient | None = None
        pages: TablePages | None = None
        retry = RETRY_S
        while not self._stop.is_set():
            try:
                if client is None:
                    self._set("asking the log warehouse")
                    client = self._connect(self.address)
                try:
                    pages = self._read(client, pages)
                except Abandoned:  # new rules: their first page next
                    continue
                self.at_start = pages.at_start
                self.repaired, self.duplicates = pages.repaired, pages.duplicates
                self._set("", "")
                retry = RETRY_S
            except WarehouseError as error:
                where = self.address.short_text(32)
                self._set("", f"the log warehouse at {where}: {error}; asking again in {retry:.0f} s")
                if client is not None:
                    client.close()
                client, pages = None, None
                self._stop.wait(retry)
                retry = min(retry * 2, MAX_RETRY_S)
                continue
            if self._asked_generation != self.generation or self._older_asked:
                continue
            due = self._prefetch_due(pages)
            if due == 0:
                continue
            waits = [wait for wait in (due, self.poll_s if self.follow else None) if wait is not None]
            self._wake.wait(min(waits) if waits else None)
            self._wake.clear()
        self._running = False
        if client is not None:
            client.close()


class WindowReader:
    """A window of the table read forward, for ``tail`` and ``convert``: ``pages()`` its rows
    oldest first (with ``max_rows`` only the newest that many), then ``newer()`` at each poll
    while following. ``WarehouseError`` when the warehouse fails."""

    def __init__(
        self,
        address: Address,
        *,
        since_ns: int | None = None,
        until_ns: int | None = None,
        rules: RuleSet | None = None,
        max_rows: int | None = None,
        page_rows: int = PAGE_ROWS,
        client: Callable[[Address], TableClient] = TableClient,
    ) -> None:
        self.address = address
        self.max_rows = max_rows
        self.page_rows = page_rows
        self.until_ns = until_ns
        self._table = client(address)
        self.pages_read = TablePages(self._table, window_condition(since_ns, until_ns, rules), source=address.text)

    def pages(self) -> Iterator[RecordColumns]:
        pages, left = self.pages_read, self.max_rows
        page = pages.first(min(self.page_rows, left or self.page_rows), within=self.max_rows)
        while len(page):
            yield page
            if left is not None:
                left -= len(page)
                if left <= 0:
                    return
            page = pages.forward(min(self.page_rows, left or self.page_rows))

    def newer(self) -> RecordColumns:
        """The rows that came since (none with ``--until``)."""
        if self.until_ns is not None:
            return RecordColumns([], [], [], [], [], [], [], [])
        return self.pages_read.newer(self.page_rows)

    def close(self) -> None:
        self._table.close()
