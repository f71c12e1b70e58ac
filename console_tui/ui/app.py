"""The console-tui Textual app: the log table, the status line and the keys."""

from __future__ import annotations

import asyncio
import os
import time
from collections import deque
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Protocol

from textual import work
from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.containers import Horizontal
from textual.notifications import SeverityLevel
from textual.screen import Screen
from textual.widgets import Footer

from ..model.formats.save import save_records
from ..model.intake_queue import IntakeQueue
from ..model.record import LogRecord
from ..model.rules.history import QueryHistory
from ..model.rules.query import parse_query
from ..model.rules.rule import RuleError
from ..model.rules.ruleset import Entry, Role, RuleSet
from ..model.rules.rulesfile import (
    last_rules_path,
    load_rules,
    query_history_path,
    save_rules,
)
from ..model.store import LogStore
from ..model.text import multi_line, one_line
from ..model.view import LogView
from ..sources.files import FileLoad
from ..sources.status import SourceStatus
from . import textual_fixes
from .exit_signals import ExitSignals
from .gc_policy import CollectionPolicy
from .screens.columns_dialog import ColumnsScreen
from .screens.detail import DetailScreen
from .screens.files import OpenScreen, PathScreen, SaveRequest, SaveScreen
from .screens.help import HelpScreen
from .screens.problems import ProblemsScreen
from .screens.quick_rule import QuickRuleScreen
from .screens.rule_editor import RuleEditor
from .widgets.load_bar import LoadBar
from .widgets.log_table import LogTable
from .widgets.logger_pane import LoggerPane
from .widgets.query_bar import QueryBar
from .widgets.rules_pane import RulesPane
from .widgets.side_pane import SidePane
from .widgets.status_bar import StatusBar, StatusFacts
from .widgets.table_columns import COLUMNS

if TYPE_CHECKING:
    from ..sources.logger_control import LoggerControl

textual_fixes.apply()

DRAIN_INTERVAL = 1 / 15
#: Background filtering after a rule change: slices of this long, with the event loop free this long between them.
REFILTER_BUDGET_S = 0.015
REFILTER_PAUSE_S = 0.001
REFILTER_FIRST_PAUSE_S = 0.02
#: How often the status line's "filtering N%" moves.
REFILTER_PROGRESS_PERIOD_S = 0.1
#: Quick rules look at this many selected rows at most.
QUICK_RULE_ROWS = 10_000
#: Records gathered per event-loop turn when saving.
SAVE_SLICE = 20_000
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
        Binding("o", "open", "Open"),
        Binding("s", "save", "Save"),
        Binding("x", "cancel_load", "Cancel load"),
        Binding("escape", "stop_filtering", "Stop a long filtering", show=False),
        Binding("exclamation_mark", "problems", "Problems", show=False),
        Binding("slash", "query", "Query"),
        Binding("r", "toggle_rules", "Rules"),
        Binding("H", "toggle_highlighted_only", "Highlighted only", show=False),
        Binding("minus", "quick_rule('exclude')", "Hide like the selected rows", show=False),
        Binding("plus", "quick_rule('highlight')", "Highlight like the selected rows", show=False),
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
        files: Sequence[str] = (),
        log_format: str | None = None,
        logger_control: LoggerControl | None = None,
        rules: RuleSet | None = None,
        query: str = "",
        remember_rules: bool = False,
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
        #: The rules in force; a new set replaces it whole (rule sets are values).
        self.rules = RuleSet()
        self._initial_rules = rules
        self._initial_query = query
        #: Keep the last rule set and the query history in the user's config folder.
        self.remember_rules = remember_rules
        self.query_history = QueryHistory.load(query_history_path()) if remember_rules else QueryHistory()
        self.query_bar = QueryBar(self.query_history, utc=utc, id="query-bar")
        self.rules_pane = RulesPane(id="rules-pane")
        self._counts_at = 0.0
        self.load_bar = LoadBar(id="load-bar")
        #: File loads: their records come through a queue of their own, ahead of live ones.
        self.file_queue = IntakeQueue()
        self.loads: list[FileLoad] = []
        self.problems: list[str] = []
        self._initial_files = list(files)
        self.log_format = log_format
        #: Started after the first frame with the sources; whoever made it closes it.
        self.logger_control = logger_control
        self.logger_pane = LoggerPane(logger_control, seen_loggers=self.store.nodes, clock=clock)
        self.exit_signals = ExitSignals(self._exit_on_signal)

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

    def copy_to_clipboard(self, text: str) -> None:
        """Copy with control characters made visible (newlines and tabs kept): pasted into a
        shell, a copied message can never carry escape sequences or a carriage return."""
        super().copy_to_clipboard(multi_line(text))

    # -- layout -------------------------------------------------------------------------------

    def compose(self) -> ComposeResult:
        with Horizontal(id="main"):
            yield self.rules_pane
            yield self.table
            yield self.logger_pane
        yield self.query_bar
        yield self.load_bar
        yield self.status_bar
        yield Footer()

    def on_mount(self) -> None:
        self.exit_signals.install()
        self.collection_policy.start()
        self.table.focus()
        self.set_interval(self.drain_interval, self.drain_intake)
        self._apply_initial_rules()
        self.update_status()
        # After the first frame: starting sources (threads, child processes) costs CPU
        # the first frame should not wait for.
        self.call_after_refresh(self.start_sources)
        if self._initial_files:
            self.open_files(self._initial_files, log_format=self.log_format)

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
        if self.remember_rules:
            self._remember_rules()
        for load in self.loads:
            load.cancel()

    def _exit_on_signal(self, signum: int) -> None:
        """SIGTERM or SIGHUP (the SSH session dropped): put temporary logger levels back
        first, whatever becomes of the terminal, then exit as ``q`` does."""
        if self.logger_control is not None:
            try:
                self.logger_control.close()
            except Exception:
                pass
        self.exit(return_code=128 + signum)

    def stop_sources(self) -> None:
        sources, self.sources = self.sources, []
        for source in sources:
            try:
                source.stop()
            except Exception:
                pass

    # -- records ----------------------------------------------------------------------------------

    def drain_intake(self) -> None:
        """Move what the sources queued into the store, in one batch per tick.

        Records from files come first; live records wait while files load, so that a
        view of files plus the live stream stays in time order."""
        records = self.file_queue.drain(MAX_RECORDS_PER_TICK)
        if not self.loading:
            records += self.queue.drain(MAX_RECORDS_PER_TICK - len(records))
        if records:
            self.add_records(records)
        if self.loads:
            self._check_loads()
        if self.rules_pane.is_open:
            self._show_rules(at_most_every=0.5)
        self.update_status()
        self.collection_policy.tick(len(records))

    # -- files --------------------------------------------------------------------------------------

    @property
    def loading(self) -> bool:
        return any(not load.finished for load in self.loads) or len(self.file_queue) > 0

    def open_files(self, paths: Sequence[str], *, log_format: str | None = None) -> FileLoad:
        """Read files in the background into the table, merged by time."""
        load = FileLoad(paths, self.file_queue, log_format=log_format)
        self.loads.append(load)
        load.start()
        self.table.set_column_shown("source", True)
        self.load_bar.show_progress([load.progress])
        return load

    def _check_loads(self) -> None:
        self.load_bar.show_progress([load.progress for load in self.loads])
        for load in [load for load in self.loads if load.finished]:
            if len(self.file_queue):
                return  # its last records are still on their way into the table
            self.loads.remove(load)
            progress = load.progress
            problems = [str(problem) for problem in load.problems()]
            self.problems.extend(problems)
            files = len(progress.files)
            verb = "Cancelled after" if progress.cancelled else "Loaded"
            text = f"{verb} {progress.records:,} records from {files} file{'s' if files != 1 else ''}"
            if problems:
                listed = "\n".join(one_line(problem, 300) for problem in problems[:3])
                more = f"\n... {len(problems) - 3} more" if len(problems) > 3 else ""
                self.notify(f"{text}, with problems (! lists them):\n{listed}{more}", severity="warning", timeout=15)
            else:
                self.notify(text, timeout=5)

    def action_open(self) -> None:
        def opened(paths: list[str] | None) -> None:
            if paths:
                self.open_files(paths, log_format=self.log_format)

        self.push_screen(OpenScreen(), opened)

    def action_cancel_load(self) -> None:
        for load in self.loads:
            load.cancel()

    def action_problems(self) -> None:
        self.push_screen(ProblemsScreen(self.problems))

    def action_save(self) -> None:
        default = os.path.join(os.getcwd(), time.strftime("console-tui-%Y%m%d-%H%M%S.csv"))

        def chosen(request: SaveRequest | None) -> None:
            if request is not None:
                self.save(request)

        self.push_screen(SaveScreen(default, filtered=self.view.filtered), chosen)

    @work(exclusive=True, group="save")
    async def save(self, request: SaveRequest) -> int:
        """Collect the rows on the UI thread a slice at a time (the store changes only
        here), then write them in a thread. Returns how many were written."""
        if request.shown_only:
            seqs = [self.view.seq_at(row) for row in range(len(self.view))]
        else:
            seqs = range(self.store.first_seq, self.store.end_seq)
        records = []
        for start in range(0, len(seqs), SAVE_SLICE):
            for seq in seqs[start : start + SAVE_SLICE]:
                if seq in self.store:
                    records.append(self.store.get(seq))
            await asyncio.sleep(0)
        lost = len(seqs) - len(records)
        try:
            written = await asyncio.to_thread(save_records, records, request.path, request.save_format)
        except (OSError, ValueError) as error:
            self.notify(f"Not saved: {error}", severity="error", timeout=15)
            return 0
        note = f" ({lost:,} dropped at the bound while saving)" if lost else ""
        self.notify(f"Saved {written:,} messages to {request.path}{note}", timeout=8)
        return written

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if action == "cancel_load":
            return self.loading
        if action == "stop_filtering":
            return self.view.refiltering
        return True

    def add_records(self, records: Iterable[LogRecord]) -> None:
        table = self.table
        with table.keeping_position():
            added = self.store.extend(records)
            self.view.update()
        if self.view.switched_off:
            self._rules_changed()
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
            note=self._rules_note(),
        )
        self.status_bar.show_facts(facts)

    def on_log_table_state_changed(self, _message: LogTable.StateChanged) -> None:
        self.update_status()

    # -- rules ----------------------------------------------------------------------------------------

    def apply_rules(self, rules: RuleSet) -> None:
        """Put ``rules`` in force: the newest screenful at once, the rest in the background."""
        with self.table.keeping_position():
            self.view.set_rules(rules)
        self._rules_changed()

    def _rules_changed(self) -> None:
        """Show the view's rules as the rules in force (the view switches off a rule too slow
        to test, and says which)."""
        table = self.table
        rules = self.rules = self.view.rules
        table.decoration_of = self.view.decoration_of if rules.highlighting else None
        table.restyle()
        for rule, why in self.view.take_switched_off():
            self.notify(f"Rule switched off, {why}: {rule.describe()}", severity="error", timeout=15)
        if self.view.refiltering:
            self._filter_in_background()
        self._show_rules()
        self.update_status()

    def action_stop_filtering(self) -> None:
        """Esc while rules are being applied: switch off the rules not applied yet."""
        with self.table.keeping_position():
            stopped = self.view.stop_filtering()
        if stopped:
            described = "; ".join(rule.describe() for rule in stopped)
            self.notify(f"Filtering stopped; switched off (r shows the rules): {described}", timeout=8)
            self._rules_changed()

    @work(exclusive=True, group="refilter")
    async def _filter_in_background(self) -> None:
        """Filter the older records in slices, newest first; between slices the event loop
        draws frames and answers keys."""
        await asyncio.sleep(REFILTER_FIRST_PAUSE_S)  # the newest screenful is drawn first
        shown_at = self.clock()
        while True:
            with self.table.keeping_position():
                done = self.view.refilter_step(REFILTER_BUDGET_S)
            if self.view.switched_off:
                self._rules_changed()  # filters again under the rules left, in a new worker
                return
            if done:
                break
            if self.clock() - shown_at >= REFILTER_PROGRESS_PERIOD_S:
                shown_at = self.clock()
                self.update_status()
            await asyncio.sleep(REFILTER_PAUSE_S)
        self._show_rules()
        self.update_status()

    def _rules_note(self) -> str:
        active = sum(1 for entry in self.rules.entries if entry.active)
        if not active:
            return "rules off" if self.rules.entries else ""
        note = f"{active} rule{'s' if active != 1 else ''}"
        if self.rules.highlighted_only and self.rules.highlighting:
            note += ", highlighted only"
        if self.view.refiltering:
            note += f", filtering {self._refilter_percent()}%"
        return note

    def _refilter_percent(self) -> int:
        total = max(len(self.store), 1)
        return min(99, int(100 * (1 - self.view.pending / total)))

    def _show_rules(self, at_most_every: float = 0.0) -> None:
        now = self.clock()
        if at_most_every and now - self._counts_at < at_most_every:
            return
        self._counts_at = now
        progress = f"filtering {self._refilter_percent()}%" if self.view.refiltering else ""
        self.rules_pane.show(self.rules, self.view.match_counts(), progress)

    def _apply_initial_rules(self) -> None:
        rules = self._initial_rules or RuleSet()
        if self._initial_query:
            try:
                rules = rules.with_query(parse_query(self._initial_query, utc=self.utc))
                self.query_bar.applied_text = self._initial_query
            except RuleError as error:
                self.notify(f"--query not applied: {error.message}", severity="error", timeout=10)
        if rules.entries:
            self.apply_rules(rules)

    def _remember_rules(self) -> None:
        try:
            save_rules(self.rules, last_rules_path())
            self.query_history.save(query_history_path())
        except OSError:
            pass  # nothing to tell anyone at exit; the rules in force were not lost from the session

    def action_query(self) -> None:
        self.query_bar.open()

    def on_query_bar_applied(self, message: QueryBar.Applied) -> None:
        self.apply_rules(self.rules.with_query(message.entries))

    def on_query_bar_closed(self, _message: QueryBar.Closed) -> None:
        self.table.focus()

    def action_toggle_rules(self) -> None:
        self._show_rules()
        self.rules_pane.toggle()

    def on_rules_pane_changed(self, message: RulesPane.Changed) -> None:
        self.apply_rules(message.rules)

    def action_toggle_highlighted_only(self) -> None:
        self.apply_rules(self.rules.with_highlighted_only(not self.rules.highlighted_only))
        state = "on" if self.rules.highlighted_only else "off"
        note = "" if self.rules.highlighting else " (no highlight rule is active, so it hides nothing)"
        self.notify(f"Highlighted only: {state}{note}", timeout=4)

    def on_rules_pane_edit_requested(self, message: RulesPane.EditRequested) -> None:
        index = message.index
        entry = self.rules.entries[index] if index is not None else None

        def edited(result: Entry | None) -> None:
            if result is None:
                return
            rules = self.rules.add(result) if index is None else self.rules.replace(index, result)
            self.apply_rules(rules)

        self.push_screen(RuleEditor(entry, utc=self.utc), edited)

    def action_quick_rule(self, role: str) -> None:
        seqs = self.table.selected_seqs(QUICK_RULE_ROWS)
        if not seqs:
            return

        def chosen(entry: Entry | None) -> None:
            if entry is not None:
                self.apply_rules(self.rules.add(entry))

        self.push_screen(QuickRuleScreen([self.store.get(seq) for seq in seqs], Role(role)), chosen)

    def on_rules_pane_file_requested(self, message: RulesPane.FileRequested) -> None:
        if message.save:
            self.action_save_rules()
        else:
            self.action_load_rules()

    def action_save_rules(self) -> None:
        def chosen(path: str | None) -> None:
            if not path:
                return
            try:
                save_rules(self.rules, path)
            except OSError as error:
                self.notify(f"Rules not saved: {error}", severity="error", timeout=10)
                return
            self.notify(f"Saved {len(self.rules.entries)} rules to {path}", timeout=5)

        default = os.path.join(os.getcwd(), "console-tui-rules.toml")
        self.push_screen(PathScreen("Save the rules to (TOML)", default), chosen)

    def action_load_rules(self, path: str | None = None) -> None:
        def chosen(path: str | None) -> None:
            if not path:
                return
            try:
                rules = load_rules(path)
            except RuleError as error:
                self.notify(f"Rules not loaded, the rules in force stay: {error.message}", severity="error", timeout=15)
                return
            self.apply_rules(rules)
            self.notify(f"Loaded {len(rules.entries)} rules from {path}", timeout=5)

        if path is not None:
            chosen(path)
        else:
            self.push_screen(PathScreen("Open rules from (TOML)", "", must_exist=True), chosen)

    def action_restore_rules(self) -> None:
        path = last_rules_path()
        if not path.exists():
            self.notify("No rule set was saved at the end of an earlier run.", timeout=5)
            return
        self.action_load_rules(str(path))

    def action_clear_rules(self) -> None:
        self.query_bar.applied_text = ""
        self.apply_rules(RuleSet(highlighted_only=self.rules.highlighted_only))

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

    def on_side_pane_leave(self, _message: SidePane.Leave) -> None:
        self.table.focus()

    # -- help and command palette ---------------------------------------------------------------

    def binding_groups(self) -> list[tuple[str, list[Binding]]]:
        return [
            ("Table", list(LogTable.BINDINGS)),
            ("Console", list(self.BINDINGS)),
            ("Rules pane", list(RulesPane.BINDINGS)),
            ("Query line", list(QueryBar.BINDINGS)),
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
        yield SystemCommand("Open files", "Log files and recordings, merged by time", self.action_open)
        yield SystemCommand(
            "Save", "Save the rows shown, or everything (rqt_console CSV or JSON Lines)", self.action_save
        )
        yield SystemCommand("Load problems", "What went wrong while loading files, and where", self.action_problems)
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
            "Logger levels of this row's node",
            "Open the logger levels pane on the selected row's node",
            self.action_loggers_for_row,
        )
        yield SystemCommand(
            "Query", 'Type rules as a query: level>=warn node:nav* -node:rviz* +"failed"', self.action_query
        )
        yield SystemCommand(
            "Rules", "Show or hide the rules pane: every rule, its switches and counts", self.action_toggle_rules
        )
        yield SystemCommand(
            "Add a rule",
            "A new exclude or highlight rule of any kind",
            lambda: self.on_rules_pane_edit_requested(RulesPane.EditRequested(None)),
        )
        yield SystemCommand(
            "Hide messages like the selected rows",
            "Exclude their nodes, severities, messages or location",
            lambda: self.action_quick_rule("exclude"),
        )
        yield SystemCommand(
            "Highlight messages like the selected rows",
            "Highlight their nodes, severities, messages or location",
            lambda: self.action_quick_rule("highlight"),
        )
        yield SystemCommand(
            "Highlighted only", "Show only highlighted messages (or all again)", self.action_toggle_highlighted_only
        )
        yield SystemCommand("Save rules", "Save the rule set to a TOML file", self.action_save_rules)
        yield SystemCommand("Open rules", "Load a rule set from a TOML file", self.action_load_rules)
        yield SystemCommand(
            "Restore the last rules", "The rule set in force when console-tui last exited", self.action_restore_rules
        )
        yield SystemCommand("Clear rules", "Remove every rule", self.action_clear_rules)
        yield SystemCommand("Keys", "Every key, on the help screen", self.action_help)
