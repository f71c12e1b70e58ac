"""The console-tui Textual app: the log table, the status line and the keys."""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Protocol

from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.containers import Horizontal
from textual.screen import Screen
from textual.widgets import Footer

from ..model.intake_queue import IntakeQueue
from ..model.record import LogRecord
from ..model.store import LogStore
from ..model.view import LogView
from ..sources.status import SourceStatus
from .gc_policy import CollectionPolicy
from .screens.columns import ColumnsScreen
from .screens.detail import DetailScreen
from .screens.help import HelpScreen
from .widgets.columns import COLUMNS
from .widgets.log_table import LogTable
from .widgets.logger_pane import LoggerPane
from .widgets.status_bar import StatusBar, StatusFacts

if TYPE_CHECKING:
    from ..sources.ros2.loggers import LoggerControl

DRAIN_INTERVAL = 1 / 15
#: Records taken into the store per tick at most, so one tick never stalls the screen.
MAX_RECORDS_PER_TICK = 20_000
RATE_WINDOW_S = 2.0


class Source(Protocol):
    """A producer of records (the live stream, a file loader) the app starts and stops."""

    status: SourceStatus

    def start(self) -> None: ...

    def stop(self) -> None: ...


class ConsoleApp(App[None]):
    """Every log message in one table, fed by sources through an ``IntakeQueue``."""

    TITLE = "console-tui"
    CSS_PATH = "app.tcss"

    BINDINGS = [
        Binding("space", "toggle_pause", "Pause"),
        Binding("c", "clear", "Clear"),
        Binding("C", "columns", "Columns"),
        Binding("l", "toggle_loggers", "Loggers"),
        Binding("L", "loggers_for_row", "Logger levels of the row's node", show=False),
        Binding("question_mark,f1", "help", "Help"),
        Binding("q", "quit", "Quit"),
        Binding("ctrl+c", "quit", "Quit", show=False),
    ]

    def __init__(
        self,
        *,
        store: LogStore | None = None,
        queue: IntakeQueue | None = None,
        sources: Sequence[Source] = (),
        utc: bool = False,
        drain_interval: float = DRAIN_INTERVAL,
        clock: Callable[[], float] = time.monotonic,
        logger_control: LoggerControl | None = None,
    ) -> None:
        super().__init__()
        self.store = store if store is not None else LogStore()
        self.queue = queue if queue is not None else IntakeQueue()
        self.view = LogView(self.store)
        self.sources = list(sources)
        self.utc = utc
        self.drain_interval = drain_interval
        self.clock = clock
        self._arrivals: deque[tuple[float, int]] = deque()
        self._rate = 0.0
        self._rate_at = 0.0
        self.collection_policy = CollectionPolicy()
        self.table = LogTable(self.store, self.view, utc=self.utc, id="log-table")
        self.status_bar = StatusBar(id="status")
        #: Started after the first frame with the sources; whoever made it closes it.
        self.logger_control = logger_control
        self.logger_pane = LoggerPane(logger_control, seen_loggers=self.store.nodes, clock=clock)

    # -- layout -------------------------------------------------------------------------------

    def compose(self) -> ComposeResult:
        with Horizontal(id="main"):
            yield self.table
            yield self.logger_pane
        yield self.status_bar
        yield Footer()

    def on_mount(self) -> None:
        self.collection_policy.start()
        self.table.focus()
        self.set_interval(self.drain_interval, self.drain_intake)
        self.update_status()
        # After the first frame: starting sources (threads, child processes) costs CPU
        # the first frame should not wait for.
        self.call_after_refresh(self.start_sources)

    def start_sources(self) -> None:
        starting: list = list(self.sources)
        if self.logger_control is not None:
            starting.append(self.logger_control)  # started here, but closed by whoever made it
        for source in starting:
            try:
                source.start()
            except Exception as error:
                self.notify(f"Could not start {type(source).__name__}: {error}", severity="error", timeout=10)

    def on_unmount(self) -> None:
        self.stop_sources()

    def stop_sources(self) -> None:
        sources, self.sources = self.sources, []
        for source in sources:
            try:
                source.stop()
            except Exception:
                pass

    # -- records ----------------------------------------------------------------------------------

    def drain_intake(self) -> None:
        """Move what the sources queued into the store, in one batch per tick."""
        records = self.queue.drain(MAX_RECORDS_PER_TICK)
        if records:
            self.add_records(records)
        self.update_status()
        self.collection_policy.tick(len(records))

    def add_records(self, records: Iterable[LogRecord]) -> None:
        table = self.table
        with table.keeping_position():
            added = self.store.extend(records)
            self.view.update()
        self._arrivals.append((self.clock(), len(added)))

    def receive_rate(self) -> float:
        """Records a second over the last ``RATE_WINDOW_S``, recomputed once a second
        (so the status line is not redrawn every tick for a changing digit)."""
        now = self.clock()
        if now - self._rate_at < 1.0:
            return self._rate
        arrivals = self._arrivals
        while arrivals and arrivals[0][0] < now - RATE_WINDOW_S:
            arrivals.popleft()
        self._rate = sum(count for _, count in arrivals) / RATE_WINDOW_S
        self._rate_at = now
        return self._rate

    def update_status(self) -> None:
        table = self.table
        statuses = [source.status for source in self.sources]
        facts = StatusFacts(
            shown=table.row_count,
            total=len(self.store),
            counts=dict(self.store.counts),
            rate=self.receive_rate(),
            following=table.following,
            paused=table.paused_end is not None,
            new_while_paused=table.new_while_paused,
            sources=statuses,
            lost=self.queue.dropped + sum(status.lost for status in statuses),
        )
        self.status_bar.show_facts(facts)

    def on_log_table_state_changed(self, _message: LogTable.StateChanged) -> None:
        self.update_status()

    # -- actions ------------------------------------------------------------------------------------

    def action_toggle_pause(self) -> None:
        table = self.table
        table.set_paused(table.paused_end is None)

    def action_clear(self) -> None:
        self.store.clear()
        self.view.rebuild()
        self.table.reset()
        self.update_status()

    def action_help(self) -> None:
        if isinstance(self.screen, HelpScreen):
            return
        self.push_screen(HelpScreen(self.binding_groups()))

    def action_columns(self) -> None:
        def apply(shown: frozenset[str] | None) -> None:
            if shown is not None:
                table = self.table
                for column in COLUMNS:
                    table.set_column_shown(column.key, column.key in shown)

        self.push_screen(ColumnsScreen(self.table.shown_columns), apply)

    def on_log_table_row_activated(self, message: LogTable.RowActivated) -> None:
        self.open_detail(message.seq)

    def open_detail(self, seq: int) -> None:
        if seq not in self.store:
            return
        self.push_screen(DetailScreen(self.store.get(seq), utc=self.utc, step=self._step_record))

    def _step_record(self, seq: int, delta: int) -> LogRecord | None:
        """The record ``delta`` rows away from ``seq`` in the table, moving the cursor too."""
        table = self.table
        row = self.view.row_of(seq) + delta
        if not 0 <= row < table.row_count:
            return None
        table.move_cursor(row)
        return self.store.get(self.view.seq_at(row))

    # -- logger levels pane ------------------------------------------------------------------

    def action_toggle_loggers(self) -> None:
        self.logger_pane.toggle()

    def action_loggers_for_row(self) -> None:
        """Open the logger levels pane on the node of the table's selected row."""
        seq = self.table.cursor_seq
        if seq is None or seq not in self.store:
            self.logger_pane.open()
        else:
            self.logger_pane.open_for_logger(self.store.get(seq).node)

    def on_logger_pane_leave(self, _message: LoggerPane.Leave) -> None:
        self.table.focus()

    # -- help and command palette ---------------------------------------------------------------

    def binding_groups(self) -> list[tuple[str, list[Binding]]]:
        return [
            ("Table", list(LogTable.BINDINGS)),
            ("Console", list(self.BINDINGS)),
            ("Logger levels pane", list(LoggerPane.BINDINGS)),
            ("Details", list(DetailScreen.BINDINGS)),
            ("Anywhere", [Binding("ctrl+p", "command_palette", "Command palette: every action by name")]),
        ]

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        yield from super().get_system_commands(screen)
        yield SystemCommand("Pause / resume", "Stop the view; messages keep arriving", self.action_toggle_pause)
        yield SystemCommand("Follow tail", "Jump to the newest message and follow it", self.table.follow)
        yield SystemCommand("Clear", "Drop every message", self.action_clear)
        yield SystemCommand("Details", "Every field of the selected message", self.table.action_activate)
        yield SystemCommand("Columns", "Choose the table's columns", self.action_columns)
        for column in COLUMNS:
            if column.key == "message":
                continue
            yield SystemCommand(
                f"Toggle column: {column.title}",
                f"Show or hide the {column.title} column",
                lambda key=column.key: self.table.set_column_shown(key, key not in self.table.shown_columns),
            )
        yield SystemCommand("Logger levels", "Show or hide the logger levels pane", self.action_toggle_loggers)
        yield SystemCommand(
            "Logger levels of this row's node", "Open the logger levels pane on the selected row's node", self.action_loggers_for_row
        )
        yield SystemCommand("Keys", "Every key, on the help screen", self.action_help)
