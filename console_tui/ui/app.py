"""The console-tui Textual app: the wiring of the table, the panes, the status line and the keys.

The app's jobs live beside it, each a part mixed into ``ConsoleApp`` (``app_part`` types what
they share): ``intake_actions`` (the sources, their records into the store), ``table_actions``
(pause, clear, columns, details), ``rule_actions`` (rules and filtering), ``file_actions``
(opening and saving files), ``pane_actions`` (the side panes), ``search_actions`` (search,
next / previous match), ``jump_actions`` (errors, warnings, marks, the source file),
``toggle_actions`` (level and node toggles, the node panel, time formats), ``overview_actions``
(the timeline, storms, the summary), ``palette`` (the command palette) and ``keys`` (the
user's keymap, hints from bindings). A feature adds its keys to ``BINDINGS`` below and its work
in a module of its own.
"""

from __future__ import annotations

import signal
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from rich.style import Style
from textual import events
from textual.app import App, ComposeResult, SystemCommand
from textual.binding import Binding
from textual.containers import Horizontal
from textual.notifications import SeverityLevel
from textual.screen import Screen

from ..model.intake_queue import IntakeQueue
from ..model.marks import Marks
from ..model.node_stats import NodeStats
from ..model.rules.history import QueryHistory
from ..model.rules.ruleset import RuleSet
from ..model.rules.rulesfile import query_history_path
from ..model.store import LogStore
from ..model.storms import StormRows
from ..model.text import multi_line, one_line
from ..model.timeline import Timeline
from ..model.view import LogView
from ..sources.fleet import Robot
from . import textual_fixes
from .app_bindings import APP_BINDINGS, NAV_KEYS, bindings_of, key_groups
from .controllers.files import FilesController
from .controllers.intake import DRAIN_INTERVAL, IntakeController, Source
from .controllers.jumps import JumpsController
from .controllers.overview import OverviewController
from .controllers.panes import PanesController
from .controllers.rules import RulesController
from .controllers.search import SearchController
from .controllers.table import TableController
from .controllers.toggles import TogglesController
from .exit_signals import ExitSignals, terminal_gone
from .focus import KeyGate, focus_now, run_bindings_now
from .gc_policy import CollectionPolicy
from .keys import binding_ids, keymap_path, load_keymap
from .palette import PaletteProvider
from .screens.help import HelpScreen
from .screens.summary import SummaryScreen
from .widgets.key_footer import KeyFooter
from .widgets.load_bar import LoadBar
from .widgets.log_table import LogTable
from .widgets.logger_pane import LoggerPane
from .widgets.node_pane import NodePane
from .widgets.query_bar import QueryBar
from .widgets.rules_pane import RulesPane
from .widgets.search_bar import SearchBar
from .widgets.side_pane import SidePane
from .widgets.status_bar import StatusBar, StatusFacts, empty_hint
from .widgets.timeline_strip import TimelineStrip

if TYPE_CHECKING:
    from ..sources.loggers.control import LoggerControl

textual_fixes.apply()


class TerminalGuard(Protocol):
    """Something holding the terminal's descriptors that lets go while the app is suspended."""

    def pause(self) -> None: ...

    def resume(self) -> None: ...


class ConsoleApp(App[None]):
    """Every log message in one table, fed by sources through an ``IntakeQueue``."""

    TITLE = "console-tui"
    CSS_PATH = "app.tcss"
    #: Textual's own palette entries (theme, quit, screenshot...) and ours.
    COMMANDS = App.COMMANDS | {PaletteProvider}

    #: Every key of the console (``app_bindings``; the help screen groups them).
    BINDINGS = APP_BINDINGS

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
        robots: Sequence[Robot] = (),
        file_robots: Mapping[str, str] | None = None,
    ) -> None:
        super().__init__()
        self.store = store if store is not None else LogStore()
        self.queue = queue if queue is not None else IntakeQueue()
        self.view = LogView(self.store)
        self.sources = list(sources)
        self.utc = utc
        self.drain_interval = drain_interval
        self.clock = clock
        self.collection_policy = CollectionPolicy(delay=drain_interval / 2)
        #: The overview's model (storms collapsed in the table, the rate over time) and strip.
        self.timeline = Timeline(self.store, self.view)
        self.storms = StormRows(self.store, self.view)
        self.timeline_strip = TimelineStrip(self.timeline, utc=utc, id="timeline")
        self.table = LogTable(self.store, self.storms, utc=self.utc, id="log-table")
        #: The fleet's robots (``--domain``, ``--master``, ``--fleet``), or none.
        self.robots = list(robots)
        self.table.robot_styles = {robot.name: Style.parse(robot.colour) for robot in robots if robot.colour}
        if len(self.robots) > 1:
            self.table.shown_columns |= {"robot"}
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
        #: File loads' records: taken in ahead of the live ones.
        self.file_queue = IntakeQueue()
        self.files = FilesController(
            self, self.store, self.view, self.table, self.load_bar, self.file_queue, log_format=log_format
        )
        self._initial_files = list(files)
        #: The robot of each file given after ``--robot NAME`` (by the path as given).
        self._file_robots = dict(file_robots or {})
        #: Started after the first frame with the sources; whoever made it closes it.
        self.logger_control = logger_control
        self.logger_pane = LoggerPane(logger_control, seen_loggers=self.store.nodes, clock=clock)
        #: Messages per node and severity, and rates: the node panel shows them.
        self.node_stats = NodeStats(self.store)
        self.node_stats.update()
        self.node_pane = NodePane(self.node_stats, lambda: self.toggles.node_toggles())
        self.exit_signals = ExitSignals(self._exit_on_signal)
        #: Binding id -> keys, from the user's keys.toml (the keys the screen names follow it).
        self.keymap: dict[str, str] = {}
        self._keymap_problems = self._load_keymap(keymap_file)
        self.key_gate = KeyGate(self)
        self._make_controllers(utc, clock)

    def _make_controllers(self, utc: bool, clock: Callable[[], float]) -> None:
        """Each controller with what it works on (the store, the view, the table, widgets, the
        controllers it hands on to), the app as its ``Host``, and the status line to update."""
        store, view, table, status = self.store, self.view, self.table, self.update_status
        self.overview = OverviewController(
            self, store, view, table, self.timeline, self.storms, self.timeline_strip, self.node_stats,
            sources=lambda: [source.status for source in self.sources], utc=utc, clock=clock, update_status=status
        )  # fmt: skip
        self.filtering = RulesController(
            self, store, view, table, self.query_bar, self.rules_pane, self.query_history, self.overview,
            utc=utc, clock=clock, update_status=status
        )  # fmt: skip
        self.table_control = TableController(
            self, store, view, table, self.marks, self.node_stats, self.overview,
            source_notes=self.files.source_notes, utc=utc, update_status=status
        )  # fmt: skip
        self.toggles = TogglesController(
            store, table, self.node_pane, rules=lambda: self.filtering.rules, apply_rules=self.filtering.apply_rules,
            live=lambda: bool(self.sources), update_status=status
        )  # fmt: skip
        self.panes = PanesController(self, store, table, self.logger_pane, self.node_pane)
        self.searching = SearchController(
            self, store, view, table, self.search_bar, self.marks, self.storms, clock=clock, update_status=status
        )
        self.intake = IntakeController(
            self, store, view, table, self.marks, self.node_stats,
            sources=self.sources, queue=self.queue, file_queue=self.file_queue, robots=self.robots,
            logger_control=self.logger_control, collection_policy=self.collection_policy,
            files=self.files, filtering=self.filtering, overview=self.overview, searching=self.searching,
            clock=clock, update_status=status
        )  # fmt: skip
        self.jumps = JumpsController(
            self, store, view, table, self.marks, opened_paths=self.files.opened_paths,
            show_marks=self.searching.show_marks, update_status=status
        )  # fmt: skip

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
    #: aside while the app is suspended (an editor has the terminal). Set by ``run_app``.
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
        yield KeyFooter()

    def on_mount(self) -> None:
        self.exit_signals.install()
        if not self.is_headless and sys.__stdin__ is not None and sys.__stdin__.isatty():
            self.set_interval(1.0, self._watch_terminal)
        if self._keymap_problems:
            listed = "\n".join(self._keymap_problems[:5])
            self.notify(f"Some keys were not remapped:\n{listed}", severity="warning", timeout=15, markup=False)
        focus_now(self.table)
        self.overview.start()
        self.set_interval(self.drain_interval, self.intake.drain_intake)
        self.filtering.apply_initial(self._initial_rules, self._initial_query)
        self.update_status()
        # After the first frame: starting sources (threads, child processes) costs CPU
        # the first frame should not wait for.
        self.call_after_refresh(self.intake.start_sources)
        self.call_after_refresh(self.collection_policy.start)  # a collection of all start-up made
        if self._initial_files:
            self.files.open_files(self._initial_files, robots=self._file_robots)

    def _load_keymap(self, keymap_file: str | None) -> tuple[str, ...]:
        """The user's keymap, in force before the widgets compose (their hints name its keys)."""
        path = keymap_path() if keymap_file is None else Path(keymap_file)
        loaded = load_keymap(path, binding_ids(self.binding_groups()))
        if loaded.keys:
            self.keymap = loaded.keys
            self.set_keymap(loaded.keys)
        return loaded.problems

    def on_unmount(self) -> None:
        self.exit_signals.remove()
        self.intake.stop_sources()
        if self.remember_rules_at_exit:
            self.filtering.remember()
        self.files.cancel_loads()

    def _watch_terminal(self) -> None:
        """A hung-up terminal whose SIGHUP never came: end as on SIGHUP (``exit_signals``)."""
        if terminal_gone(sys.__stdin__.fileno()):  # type: ignore[union-attr]
            self._exit_on_signal(signal.SIGHUP)

    def _exit_on_signal(self, signum: int) -> None:
        """SIGTERM or SIGHUP (the SSH session dropped): put temporary logger levels back
        first, whatever becomes of the terminal, then exit as ``q`` does."""
        if self.logger_control is not None:
            try:
                self.logger_control.close()
            except Exception:
                pass
        self.intake.begin_stopping_sources()
        self.exit(return_code=128 + signum)

    async def action_quit(self) -> None:
        self.intake.begin_stopping_sources()
        self.exit()

    def update_status(self) -> None:
        table = self.table
        statuses = [source.status for source in self.sources]
        paused_end = table.paused_end
        facts = StatusFacts(
            # Messages, not rows: a storm's row shows many.
            shown=len(self.view) if paused_end is None else self.view.count_before(paused_end),
            total=len(self.store),
            counts=dict(self.store.counts),
            rate=self.intake.receive_rate(),
            following=table.following,
            paused=table.paused_end is not None,
            new_while_paused=table.new_while_paused,
            sources=statuses,
            note=", ".join(note for note in (self.filtering.note(), self.overview.note()) if note),
            search=self.searching.search_status(),
            toggles=self.toggles.status(),
            time=self.toggles.time_status(),
        )
        self.status_bar.show_facts(facts)
        table.show_hint(empty_hint(facts, self.view.refiltering))
        self._refresh_footer()

    _footer_state: tuple[bool | None, ...] = ()

    def _refresh_footer(self) -> None:
        """The footer's keys that come and go (``check_action``) follow the app's state when
        it changes (a load ends, filtering is done), not only when the focus moves."""
        actions = ("pause", "cancel_load", "stop_filtering", "clear_search")
        state = tuple(self.check_action(action, ()) for action in actions)
        if state != self._footer_state:
            self._footer_state = state
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
        if action == "pause":
            return self.table.paused_end is None
        if action == "resume":
            return self.table.paused_end is not None
        if action == "cancel_load":
            return self.files.loading
        if action == "stop_filtering":
            return self.view.refiltering
        if action == "clear_search":
            return self.searching.search is not None and not self.view.refiltering
        return True

    # -- the table (``controllers.table``) -------------------------------------------------------

    def action_pause(self) -> None:
        self.table.set_paused(True)

    def action_resume(self) -> None:
        self.table.set_paused(False)

    def action_toggle_pause(self) -> None:
        self.table.set_paused(self.table.paused_end is None)

    def action_follow(self) -> None:
        self.table.follow()

    def on_log_table_state_changed(self, _message: LogTable.StateChanged) -> None:
        self.update_status()  # the footer's Pause or Resume too
        self.overview.show(force=True)

    def action_clear(self) -> None:
        self.table_control.clear()

    def action_columns(self) -> None:
        self.table_control.ask_columns()

    def action_toggle_column(self, key: str) -> None:
        self.table_control.toggle_column(key)

    def action_details(self) -> None:
        self.table.action_activate()

    def on_log_table_row_activated(self, message: LogTable.RowActivated) -> None:
        self.table_control.open_detail(message.seq)

    # -- rules (``controllers.rules``) -----------------------------------------------------------

    def action_query(self) -> None:
        self.query_bar.open()

    def on_query_bar_applied(self, message: QueryBar.Applied) -> None:
        self.filtering.query_applied(message)

    def on_query_bar_closed(self, _message: QueryBar.Closed) -> None:
        focus_now(self.table)

    def action_toggle_rules(self) -> None:
        self.filtering.toggle_pane()

    def on_rules_pane_changed(self, message: RulesPane.Changed) -> None:
        self.filtering.apply_rules(message.rules)

    def on_rules_pane_edit_requested(self, message: RulesPane.EditRequested) -> None:
        self.filtering.edit_rule(message.index)

    def on_rules_pane_file_requested(self, message: RulesPane.FileRequested) -> None:
        if message.save:
            self.filtering.ask_save()
        else:
            self.filtering.open_rules()

    def action_stop_filtering(self) -> None:
        self.filtering.stop_filtering()

    def action_toggle_highlighted_only(self) -> None:
        self.filtering.toggle_highlighted_only()

    def action_add_rule(self) -> None:
        self.filtering.edit_rule(None)

    def action_quick_rule(self, role: str) -> None:
        self.filtering.quick_rule(role)

    def action_clear_rules(self) -> None:
        self.filtering.clear_rules()

    def action_save_rules(self) -> None:
        self.filtering.ask_save()

    def action_load_rules(self, path: str | None = None) -> None:
        self.filtering.open_rules(path)

    def action_restore_rules(self) -> None:
        self.filtering.restore_rules()

    # -- files (``controllers.files``) -----------------------------------------------------------

    def action_open(self) -> None:
        self.files.ask_open()

    def action_cancel_load(self) -> None:
        self.files.cancel_loads()

    def action_problems(self) -> None:
        self.files.show_problems()

    def action_save(self) -> None:
        self.files.ask_save()

    # -- toggles (``controllers.toggles``) and the side panes (``controllers.panes``) ---------------

    def action_toggle_level(self, level: int) -> None:
        self.toggles.toggle_level(level)

    def action_raise_minimum(self) -> None:
        self.toggles.raise_minimum()

    def action_lower_minimum(self) -> None:
        self.toggles.lower_minimum()

    def action_all_levels(self) -> None:
        self.toggles.all_levels()

    def action_minimum_level(self, level: int) -> None:
        self.toggles.minimum_level(level)

    def on_node_pane_toggle(self, message: NodePane.Toggle) -> None:
        self.toggles.node_panel_toggle(message)

    def action_solo_row_node(self) -> None:
        self.toggles.solo_row_node()

    def action_mute_row_node(self) -> None:
        self.toggles.mute_row_node()

    def action_clear_node_toggles(self) -> None:
        self.toggles.clear_node_toggles()

    def action_next_time_format(self) -> None:
        self.toggles.next_time_format()

    def action_time_format(self, name: str) -> None:
        self.toggles.time_format(name)

    def action_toggle_utc(self) -> None:
        self.toggles.toggle_utc()

    def action_toggle_loggers(self) -> None:
        self.panes.toggle_loggers()

    def action_toggle_nodes(self) -> None:
        self.panes.toggle_nodes()

    def action_loggers_for_row(self) -> None:
        self.panes.loggers_for_row()

    def on_logger_pane_temporary_requested(self, message: LoggerPane.TemporaryRequested) -> None:
        self.panes.ask_temporary_level(message)

    def on_side_pane_leave(self, _message: SidePane.Leave) -> None:
        focus_now(self.table)

    # -- the overview (``controllers.overview``) -------------------------------------------------

    def action_toggle_timeline(self) -> None:
        self.overview.toggle_timeline()

    def action_timeline(self) -> None:
        self.overview.pick_time()

    def on_timeline_strip_jump(self, message: TimelineStrip.Jump) -> None:
        self.overview.show_seq(message.seq)

    def on_timeline_strip_leave(self, _message: TimelineStrip.Leave) -> None:
        focus_now(self.table)

    def action_toggle_storm(self) -> None:
        self.overview.toggle_storm()

    def action_toggle_storms(self) -> None:
        self.overview.toggle_storms()

    def action_toggle_mask_digits(self) -> None:
        self.overview.toggle_mask_digits()

    def action_summary(self) -> None:
        if not isinstance(self.screen, SummaryScreen):
            self.overview.summary()

    # -- search (``controllers.search``) --------------------------------------------------------

    def action_search(self) -> None:
        self.searching.open_search_line()

    def on_search_bar_changed(self, message: SearchBar.Changed) -> None:
        self.searching.search_line_changed(message)

    def on_search_bar_done(self, message: SearchBar.Done) -> None:
        self.searching.search_line_done(message)

    def action_clear_search(self) -> None:
        if self.searching.search is not None:
            self.searching.clear_search()

    def action_next_match(self) -> None:
        self.searching.jump_to_match(forward=True)

    def action_previous_match(self) -> None:
        self.searching.jump_to_match(forward=False)

    # -- jumps (``controllers.jumps``) ---------------------------------------------------------

    def action_next_level(self, level: int) -> None:
        self.jumps.next_level(level)

    def action_previous_level(self, level: int) -> None:
        self.jumps.previous_level(level)

    def action_first_row(self) -> None:
        self.table.action_first_row()

    def action_last_row(self) -> None:
        self.table.follow()

    def action_toggle_mark(self) -> None:
        self.jumps.toggle_mark()

    def action_next_mark(self) -> None:
        self.jumps.to_mark(forward=True)

    def action_previous_mark(self) -> None:
        self.jumps.to_mark(forward=False)

    def action_marks(self) -> None:
        self.jumps.list_marks()

    def action_open_source(self) -> None:
        self.jumps.open_source()

    # -- help and the command palette -------------------------------------------------------------

    def action_help(self) -> None:
        if isinstance(self.screen, HelpScreen):
            return
        self.push_screen(HelpScreen(self.binding_groups()))

    def binding_groups(self) -> list[tuple[str, list[Binding]]]:
        """Every key, by where it works: the help screen, the keymap and the palette read these."""
        return key_groups()

    def nav_bindings(self) -> list[Binding]:
        """The keys that find your way: search, jumps, marks, levels, nodes, time (the search
        line's hint names them)."""
        return bindings_of(NAV_KEYS)

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        # Textual's "Keys" opens its key panel; "Help: every key" (ours) says more.
        yield from (command for command in super().get_system_commands(screen) if command.title != "Keys")
