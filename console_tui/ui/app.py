"""The console-tui Textual app: the wiring of the table, the panes, the status line and the keys.

The app's jobs live beside it, each mixed into ``ConsoleApp``: ``rule_actions`` (rules and
filtering), ``file_actions`` (opening and saving files), ``pane_actions`` (the side panes),
``search_actions`` (search, next / previous match), ``jump_actions`` (errors, warnings, marks,
the source file), ``toggle_actions`` (level and node toggles, the node panel, time formats),
``commands`` (the command palette) and ``keys`` (the user's keymap, hints from bindings).
A feature adds its keys to ``BINDINGS`` below and its work in a module of its own.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from textual import events
from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding, BindingType
from textual.containers import Horizontal
from textual.notifications import SeverityLevel
from textual.screen import Screen
from textual.widgets import Footer

from ..model.intake_queue import IntakeQueue
from ..model.marks import Marks
from ..model.node_stats import NodeStats
from ..model.record import LogRecord
from ..model.record_batch import RecordColumns
from ..model.rules.history import QueryHistory
from ..model.rules.ruleset import RuleSet
from ..model.rules.rulesfile import query_history_path
from ..model.store import LogStore
from ..model.text import multi_line, one_line
from ..model.view import LogView
from ..sources.files import FileLoad
from ..sources.status import SourceStatus
from . import textual_fixes
from .commands import ConsoleCommands
from .exit_signals import ExitSignals
from .file_actions import FileActions
from .focus import KeyGate, focus_now, run_bindings_now
from .gc_policy import CollectionPolicy
from .jump_actions import JumpActions
from .keys import binding_ids, keymap_path, load_keymap
from .overview_actions import OverviewActions
from .pane_actions import PaneActions
from .rule_actions import RuleActions
from .screens.columns_dialog import ColumnsScreen
from .screens.detail import DetailScreen
from .screens.help import HelpScreen
from .screens.mark_list import MarksScreen
from .screens.summary import SummaryScreen
from .search_actions import SearchActions
from .toggle_actions import ToggleActions
from .widgets.load_bar import LoadBar
from .widgets.log_table import LogTable
from .widgets.logger_pane import LoggerPane
from .widgets.node_pane import NodePane
from .widgets.query_bar import QueryBar
from .widgets.rules_pane import RulesPane
from .widgets.search_bar import SearchBar
from .widgets.status_bar import StatusBar, StatusFacts, empty_hint
from .widgets.table_columns import COLUMNS
from .widgets.timeline_strip import TimelineStrip

if TYPE_CHECKING:
    from ..sources.logger_control import LoggerControl

textual_fixes.apply()

DRAIN_INTERVAL = 1 / 15
#: Records taken into the store per tick at most, so one tick never stalls the screen.
MAX_RECORDS_PER_TICK = 20_000
RATE_WINDOW_S = 2.0
#: How long quitting waits for the sources to stop, at most.
SOURCE_STOP_TIMEOUT_S = 2.0


def _stop_quietly(source: Source) -> None:
    try:
        source.stop()
    except Exception:
        pass


class TerminalGuard(Protocol):
    """Something holding the terminal's descriptors that lets go while the app is suspended."""

    def pause(self) -> None: ...

    def resume(self) -> None: ...


class Source(Protocol):
    """A producer of records (the live stream, a file loader) the app starts and stops."""

    status: SourceStatus

    def start(self) -> None: ...

    def stop(self) -> None: ...


class ConsoleApp(RuleActions, FileActions, PaneActions, SearchActions, JumpActions, ToggleActions, OverviewActions):
    """Every log message in one table, fed by sources through an ``IntakeQueue``."""

    TITLE = "console-tui"
    CSS_PATH = "app.tcss"
    #: Textual's own palette entries (theme, quit, screenshot...) and ours.
    COMMANDS = App.COMMANDS | {ConsoleCommands}

    BINDINGS = [
        # Named for what it does now: the footer says Resume while paused (name_pause_key).
        Binding("space", "toggle_pause", "Pause", id="console.pause"),
        Binding("c", "clear", "Clear", id="console.clear"),
        Binding("o", "open", "Open", id="console.open"),
        Binding("s", "save", "Save", id="console.save"),
        Binding("x", "cancel_load", "Cancel load", id="console.cancel_load"),
        Binding("escape", "stop_filtering", "Stop a long filtering", show=False, id="console.stop_filtering"),
        Binding("escape", "clear_search", "Clear the search", show=False, id="console.clear_search"),
        Binding("exclamation_mark", "problems", "Problems", show=False, id="console.problems"),
        Binding("slash", "query", "Query", id="console.query"),
        *SearchActions.KEYS,
        Binding("r", "toggle_rules", "Rules", id="console.rules"),
        Binding("H", "toggle_highlighted_only", "Highlighted only", show=False, id="console.highlighted_only"),
        Binding("minus", "quick_rule('exclude')", "Hide like the selected rows", show=False, id="console.hide_like"),
        Binding(
            "plus",
            "quick_rule('highlight')",
            "Highlight like the selected rows",
            show=False,
            id="console.highlight_like",
        ),
        Binding("C", "columns", "Columns", id="console.columns"),
        Binding("l", "toggle_loggers", "Loggers", id="console.loggers"),
        Binding("ctrl+n", "toggle_nodes", "Nodes", id="console.nodes"),
        Binding("L", "loggers_for_row", "Logger levels of the row's node", show=False, id="console.loggers_for_row"),
        Binding("T", "timeline", "Timeline: pick a time to show", show=False, id="overview.timeline"),
        Binding("ctrl+t", "toggle_timeline", "Show / hide the timeline", show=False, id="overview.toggle_timeline"),
        Binding("z", "toggle_storm", "Expand / collapse the row's storm", show=False, id="overview.storm"),
        Binding("Z", "toggle_storms", "Storms collapsed on / off", show=False, id="overview.storms"),
        Binding("S", "summary", "Summary of the run", show=False, id="overview.summary"),
        Binding("question_mark,f1", "help", "Help", id="console.help"),
        Binding("q", "quit", "Quit", id="console.quit"),
        Binding("ctrl+c", "quit", "Quit", show=False),
        *JumpActions.KEYS,
        *ToggleActions.KEYS,
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
        files: Sequence[str] = (),
        log_format: str | None = None,
        logger_control: LoggerControl | None = None,
        rules: RuleSet | None = None,
        query: str = "",
        remember_rules: bool = False,
        keymap_file: str | None = None,
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
        rows = self.make_overview(self.store, self.view, utc)
        self.table = LogTable(self.store, rows, utc=self.utc, id="log-table")
        self.status_bar = StatusBar(id="status")
        self._initial_rules = rules
        self._initial_query = query
        #: Keep the last rule set and the query history in the user's config folder.
        self.remember_rules_at_exit = remember_rules
        self.query_history = QueryHistory.load(query_history_path()) if remember_rules else QueryHistory()
        self.query_bar = QueryBar(self.query_history, utc=utc, id="query-bar")
        self.search_bar = SearchBar(id="search-bar")
        self.marks = Marks()
        self.rules_pane = RulesPane(id="rules-pane")
        self.load_bar = LoadBar(id="load-bar")
        self.file_queue = IntakeQueue()
        self.loads: list[FileLoad] = []
        self.problems: list[str] = []
        self.source_notes: dict[str, list[str]] = {}
        self._initial_files = list(files)
        self.log_format = log_format
        #: Started after the first frame with the sources; whoever made it closes it.
        self.logger_control = logger_control
        self.logger_pane = LoggerPane(logger_control, seen_loggers=self.store.nodes, clock=clock)
        #: Messages per node and severity, and rates: the node panel shows them.
        self.node_stats = NodeStats(self.store)
        self.node_stats.update()
        self.node_pane = NodePane(self.node_stats, self.node_toggles)
        self.exit_signals = ExitSignals(self._exit_on_signal)
        #: The threads stopping the sources, once quitting began.
        self._stopping: list[threading.Thread] = []
        #: Binding id -> keys, from the user's keys.toml (the keys the screen names follow it).
        self.keymap: dict[str, str] = {}
        self._keymap_problems = self._load_keymap(keymap_file)
        self.key_gate = KeyGate(self)
        self._shown_paused = False

    # -- text from outside: never markup, never raw ----------------------------------------------

    def notify(
        self,
        message: str,
        *,
        title: str = "",
        severity: SeverityLevel = "information",
        timeout: float | None = None,
        markup: bool = False,
    ) -> None:
        """Every notification (ours, the screens', Textual's) as plain, inert text: messages
        name files, nodes and errors from outside, which may hold markup or escapes."""
        super().notify(multi_line(message), title=one_line(title), severity=severity, timeout=timeout, markup=False)

    #: What catches native code's output while the app draws (``sources.native_output``): put
    #: aside while the app is suspended (an editor has the terminal). Set by the launch.
    native_output: TerminalGuard | None = None

    @contextmanager
    def suspend(self) -> Iterator[None]:
        guard = self.native_output
        if guard is not None:
            guard.pause()
        try:
            with super().suspend():
                yield
        finally:
            if guard is not None:
                guard.resume()

    def copy_to_clipboard(self, text: str) -> None:
        """Copy with control characters made visible (newlines and tabs kept): pasted into a
        shell, a copied message can never carry escape sequences or a carriage return."""
        super().copy_to_clipboard(multi_line(text))

    # -- layout -------------------------------------------------------------------------------

    def compose(self) -> ComposeResult:
        yield self.timeline_strip
        with Horizontal(id="main"):
            yield self.rules_pane
            yield self.table
            yield self.logger_pane
            yield self.node_pane
        yield self.query_bar
        yield self.search_bar
        yield self.load_bar
        yield self.status_bar
        yield Footer()

    def on_mount(self) -> None:
        self.exit_signals.install()
        self.collection_policy.start()
        if self._keymap_problems:
            listed = "\n".join(self._keymap_problems[:5])
            self.notify(f"Some keys were not remapped:\n{listed}", severity="warning", timeout=15, markup=False)
        focus_now(self.table)
        self.start_overview()
        self.set_interval(self.drain_interval, self.drain_intake)
        self.apply_initial_rules(self._initial_rules, self._initial_query)
        self.update_status()
        # After the first frame: starting sources (threads, child processes) costs CPU
        # the first frame should not wait for.
        self.call_after_refresh(self.start_sources)
        if self._initial_files:
            self.open_files(self._initial_files, log_format=self.log_format)

    def _load_keymap(self, keymap_file: str | None) -> tuple[str, ...]:
        """The user's keymap, in force before the widgets compose (their hints name its keys)."""
        path = keymap_path() if keymap_file is None else Path(keymap_file)
        loaded = load_keymap(path, binding_ids(self.binding_groups()))
        if loaded.keys:
            self.keymap = loaded.keys
            self.set_keymap(loaded.keys)
        return loaded.problems

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
        self.exit_signals.remove()
        self.stop_sources()
        if self.remember_rules_at_exit:
            self.remember_rules()
        self.cancel_loads()

    def _exit_on_signal(self, signum: int) -> None:
        """SIGTERM or SIGHUP (the SSH session dropped): put temporary logger levels back
        first, whatever becomes of the terminal, then exit as ``q`` does."""
        if self.logger_control is not None:
            try:
                self.logger_control.close()
            except Exception:
                pass
        self.begin_stopping_sources()
        self.exit(return_code=128 + signum)

    def begin_stopping_sources(self) -> None:
        """Start stopping every source, all at once, each in a thread of its own: each may
        wait a moment for a process of its own (the intake process, demo nodes) to end, and
        that runs while Textual takes the screens down, not after."""
        sources, self.sources = self.sources, []
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

    async def action_quit(self) -> None:
        self.begin_stopping_sources()
        self.exit()

    # -- records ----------------------------------------------------------------------------------

    def drain_intake(self) -> None:
        """Move what the sources queued into the store, in one batch per tick.

        Records from files come first; live records wait while files load, so that a
        view of files plus the live stream stays in time order."""
        batches = self.file_queue.drain_batches(MAX_RECORDS_PER_TICK)
        if not self.loading:
            room = MAX_RECORDS_PER_TICK - sum(map(len, batches))
            batches += self.queue.drain_batches(room)
        arrived = self.add_batches(batches) if batches else 0
        if self.loads:
            self.check_loads()
        if self.rules_pane.is_open:
            self.show_rules(at_most_every=0.5)
        self.update_status()
        self.show_overview()
        self.collection_policy.tick(arrived)

    def add_records(self, records: Iterable[LogRecord]) -> None:
        self.add_batches([records if isinstance(records, list) else list(records)])

    def add_batches(self, batches: Sequence[list[LogRecord] | RecordColumns]) -> int:
        """Put batches (records, or records in columns) into the store and the view; how many."""
        table = self.table
        added = 0
        with table.keeping_position():
            for batch in batches:
                added += len(self.store.extend(batch))
            self.view.update()
            self.follow_overview()
        if self.view.switched_off:
            self.rules_changed()
        self._arrivals.append((self.clock(), added))
        self.node_stats.update()
        self.search_after_records()
        return added

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
        paused_end = table.paused_end
        facts = StatusFacts(
            # Messages, not rows: a storm's row shows many.
            shown=len(self.view) if paused_end is None else self.view.count_before(paused_end),
            total=len(self.store),
            counts=dict(self.store.counts),
            rate=self.receive_rate(),
            following=table.following,
            paused=table.paused_end is not None,
            new_while_paused=table.new_while_paused,
            sources=statuses,
            note=", ".join(note for note in (self.rules_note(), self.storms_note()) if note),
            search=self.search_status(),
            toggles=self.toggles_status(),
            time=self.time_status(),
        )
        self.status_bar.show_facts(facts)
        table.show_hint(empty_hint(facts, self.view.refiltering))

    def on_log_table_state_changed(self, _message: LogTable.StateChanged) -> None:
        self.update_status()
        self.show_overview(force=True)
        paused = self.table.paused_end is not None
        if paused != self._shown_paused:
            self._shown_paused = paused
            self.name_pause_key(paused)

    def name_pause_key(self, paused: bool) -> None:
        """The footer names what the pause key does now: Pause, or Resume while paused. (The
        app's own bindings are changed in place; a keymap applies over them as before.)"""
        words = "Resume" if paused else "Pause"
        table = self._bindings.key_to_bindings
        for key, bindings in table.items():
            table[key] = [replace(b, description=words) if b.id == "console.pause" else b for b in bindings]
        self.refresh_bindings()

    async def on_event(self, event: events.Event) -> None:
        # Keys typed ahead go where they were meant (see focus.py): they wait while the screen
        # on top is not ready for them, and while the table has the focus a key's binding runs
        # at once, so that the keys behind it find the focus where it put it.
        if isinstance(event, events.Key) and not event.is_forwarded:
            if self.key_gate.hold(event):
                return
            if self.focused is self.table and await run_bindings_now(self, event):
                return
        await super().on_event(event)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if action == "cancel_load":
            return self.loading
        if action == "stop_filtering":
            return self.view.refiltering
        if action == "clear_search":
            return self.search is not None and not self.view.refiltering
        return True

    # -- the table --------------------------------------------------------------------------------

    def action_toggle_pause(self) -> None:
        table = self.table
        table.set_paused(table.paused_end is None)

    def action_follow(self) -> None:
        self.table.follow()

    def action_clear(self) -> None:
        self.marks.clear()
        self.store.clear()
        self.node_stats.clear()
        self.view.rebuild()
        self.clear_overview()
        self.table.reset()
        self.update_status()

    def action_columns(self) -> None:
        def apply(shown: frozenset[str] | None) -> None:
            if shown is not None:
                table = self.table
                for column in COLUMNS:
                    table.set_column_shown(column.key, column.key in shown)

        self.push_screen(ColumnsScreen(self.table.shown_columns), apply)

    def action_toggle_column(self, key: str) -> None:
        self.table.set_column_shown(key, key not in self.table.shown_columns)

    def action_details(self) -> None:
        self.table.action_activate()

    def on_log_table_row_activated(self, message: LogTable.RowActivated) -> None:
        self.open_detail(message.seq)

    def open_detail(self, seq: int) -> None:
        if seq not in self.store:
            return
        self.push_screen(
            DetailScreen(self.store.get(seq), utc=self.utc, step=self._step_record, source_notes=self.source_notes)
        )

    def _step_record(self, seq: int, delta: int) -> LogRecord | None:
        """The record ``delta`` rows away from ``seq`` in the table, moving the cursor too."""
        table = self.table
        row = table.view.row_of(seq) + delta
        if not 0 <= row < table.row_count:
            return None
        table.move_cursor(row)
        return self.store.get(table.view.seq_at(row))

    # -- help and the command palette -------------------------------------------------------------

    def action_help(self) -> None:
        if isinstance(self.screen, HelpScreen):
            return
        self.push_screen(HelpScreen(self.binding_groups()))

    def binding_groups(self) -> list[tuple[str, list[Binding]]]:
        """Every key, by where it works: the help screen, the keymap and the palette read these."""
        nav = self.nav_bindings()
        return [
            ("Table", _bindings(LogTable.BINDINGS)),
            ("Console", [binding for binding in _bindings(ConsoleApp.BINDINGS) if binding not in nav]),
            ("Find your way", nav),
            ("Search line", _bindings(SearchBar.BINDINGS)),
            ("Node panel", _bindings(NodePane.BINDINGS)),
            ("Marks", _bindings(MarksScreen.BINDINGS)),
            ("Rules pane", _bindings(RulesPane.BINDINGS)),
            ("Query line", _bindings(QueryBar.BINDINGS)),
            ("Logger levels pane", _bindings(LoggerPane.BINDINGS)),
            ("Timeline", _bindings(TimelineStrip.BINDINGS)),
            ("Summary", _bindings(SummaryScreen.BINDINGS)),
            ("Details", _bindings(DetailScreen.BINDINGS)),
            ("Anywhere", [Binding("ctrl+p", "command_palette", "Command palette: every action by name")]),
        ]

    def nav_bindings(self) -> list[Binding]:
        """The keys that find your way: search, jumps, marks, levels, nodes, time."""
        return _bindings([*SearchActions.KEYS, *JumpActions.KEYS, *ToggleActions.KEYS])

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        # Textual's "Keys" opens its key panel; "Help: every key" (ours) says more.
        yield from (command for command in super().get_system_commands(screen) if command.title != "Keys")


def _bindings(bindings: Iterable[BindingType]) -> list[Binding]:
    return [binding for binding in bindings if isinstance(binding, Binding)]
