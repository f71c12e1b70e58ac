"""The console: the screen of the log table, its panes and lines, and the controllers behind them.

``ConsoleScreen`` composes the widgets (the timeline strip, the rules pane, the table, the
logger levels pane and the node panel, the query and search lines, the load bar, the status
line, the footer), owns one controller a concern (``controllers``: intake, table, rules, files,
panes, search, jumps, toggles, overview, warehouse), each made with the few things it works on, and hands
the widgets' messages to them. Their commands (``command_table``) are gathered here in
``commands``; the app binds their keys.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING

from rich.style import Style
from textual import on
from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.screen import Screen

from ..model.overview.node_stats import NodeStats
from ..model.overview.storms import StormRows
from ..model.overview.timeline import Timeline
from ..model.rules.history import QueryHistory
from ..model.rules.ruleset import RuleSet
from ..model.store.history_status import history_state
from ..model.store.intake_queue import IntakeQueue
from ..model.store.log_store import LogStore
from ..model.view.log_view import LogView
from ..model.view.marks import Marks
from ..ros.fleet import Robot
from .command_table import CommandTable
from .controllers.announcements import Announcements
from .controllers.context import ConsoleContext
from .controllers.files import FilesController
from .controllers.host import TerminalHost
from .controllers.intake import IntakeController, Source
from .controllers.jumps import JumpsController
from .controllers.overview import OverviewController
from .controllers.panes import PanesController
from .controllers.rules import RulesController
from .controllers.search import SearchController
from .controllers.table import TableController
from .controllers.toggles import TogglesController
from .controllers.warehouse import WarehouseController, warehouses_of
from .focus import focus_now
from .gc_policy import CollectionPolicy
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
    from ..control.control_thread import LoggerControl


class ConsoleScreen(Screen[None]):
    """Every log message in one table, fed by sources through an ``IntakeQueue``."""

    def __init__(
        self,
        host: TerminalHost,
        *,
        controllers: Sequence[type],
        store: LogStore,
        queue: IntakeQueue,
        sources: Sequence[Source],
        utc: bool,
        clock: Callable[[], float],
        drain_interval: float,
        collection_policy: CollectionPolicy,
        query_history: QueryHistory,
        files: Sequence[str] = (),
        log_format: str | None = None,
        logger_control: LoggerControl | None = None,
        rules: RuleSet | None = None,
        query: str = "",
        robots: Sequence[Robot] = (),
        file_robots: Mapping[str, str] | None = None,
    ) -> None:
        super().__init__()
        self.store = store
        self.queue = queue
        self.view = LogView(self.store)
        self.sources = list(sources)
        self.collection_policy = collection_policy
        self._drain_interval = drain_interval
        #: The overview's model (storms collapsed in the table, the rate over time) and strip.
        self.timeline = Timeline(self.store, self.view)
        self.storms = StormRows(self.store, self.view)
        self.timeline_strip = TimelineStrip(self.timeline, utc=utc, id="timeline")
        self.table = LogTable(self.store, self.storms, utc=utc, id="log-table")
        #: The fleet's robots (``--domain``, ``--master``, ``--fleet``), or none.
        self.robots = list(robots)
        self.table.painter.robot_styles = {robot.name: Style.parse(robot.colour) for robot in robots if robot.colour}
        #: The Robot column from the start: a fleet's robots, or a log warehouse's (a fleet's
        #: logs, even when the rows asked for are one robot's).
        self._robot_column = len(self.robots) > 1 or bool(warehouses_of(self.sources))
        if self._robot_column:
            self.table.painter.set_column_shown("robot", True)
        self.status_bar = StatusBar(id="status")
        self._initial_rules = rules
        self._initial_query = query
        self.query_history = query_history
        self.query_bar = QueryBar(query_history, utc=utc, id="query-bar")
        self.search_bar = SearchBar(id="search-bar")
        self.marks = Marks()
        self.rules_pane = RulesPane(id="rules-pane")
        self.load_bar = LoadBar(id="load-bar")
        #: File loads' records: taken in ahead of the live ones.
        self.file_queue = IntakeQueue()
        self._initial_files = list(files)
        #: The robot of each file given after ``--robot NAME`` (by the path as given).
        self._file_robots = dict(file_robots or {})
        self.logger_pane = LoggerPane(logger_control, seen_loggers=self.store.nodes, clock=clock)
        #: Messages per node and severity, and rates: the node panel shows them.
        self.node_stats = NodeStats(self.store)
        self.node_pane = NodePane(self.node_stats, lambda: self.toggles.node_toggles())
        #: What every controller works on (``controllers.context``).
        self.context = ConsoleContext(
            host=host,
            store=self.store,
            view=self.view,
            table=self.table,
            marks=self.marks,
            clock=clock,
            utc=utc,
            changed=self.state_changed,
            announce=Announcements(),
        )
        made = {type(controller): controller for controller in self._make_controllers(log_format)}
        #: Every controller's commands, in the order of ``controllers`` (those not made by
        #: ``_make_controllers`` need only the context: made here).
        self.commands = CommandTable()
        for kind in controllers:
            self.commands.add(made[kind] if kind in made else kind(self.context))
        # The collector's turn comes with the intake's tick, after everything else it does.
        self.context.announce.tick.subscribe(collection_policy.tick)

    def _make_controllers(self, log_format: str | None) -> list[object]:
        """Each controller with the context and the few things only it drives. They subscribe
        to what they follow as they are made: the order here is the order they hear news in
        (the rules before the table, the table before the search: a late history's rows are
        drawn again before the search starts again over them)."""
        context = self.context
        self.files = FilesController(context, self.load_bar, self.file_queue, log_format=log_format)
        self.overview = OverviewController(
            context,
            self.timeline,
            self.storms,
            self.timeline_strip,
            self.node_stats,
            sources=lambda: [source.status for source in self.sources],
        )
        self.filtering = RulesController(context, self.query_bar, self.rules_pane, self.query_history)
        self.table_control = TableController(
            context, source_notes=self.files.source_notes, robot_column=self._robot_column
        )
        self.toggles = TogglesController(
            context,
            self.node_pane,
            rules=lambda: self.filtering.rules,
            apply_rules=self.filtering.apply_rules,
            live=lambda: bool(self.sources),
        )
        self.panes = PanesController(context, self.logger_pane, self.node_pane)
        self.searching = SearchController(context, self.search_bar, self.storms)
        self.intake = IntakeController(
            context,
            sources=self.sources,
            queue=self.queue,
            file_queue=self.file_queue,
            files_loading=lambda: self.files.loading,
            robots=self.robots,
        )
        self.jumps = JumpsController(context, opened_paths=self.files.opened_paths)
        self.warehouse = WarehouseController(
            context,
            self.intake,
            sources=self.sources,
            reapply_rules=lambda: self.filtering.apply_rules(self.filtering.rules),
        )
        return [
            self.files,
            self.overview,
            self.filtering,
            self.table_control,
            self.toggles,
            self.panes,
            self.searching,
            self.intake,
            self.jumps,
            self.warehouse,
        ]

    #: Whether the panes and lines hidden at start are mounted (``_mount_hidden``): until
    #: then keys wait (``focus.KeyGate``) and nothing is drained into the table.
    ready_for_keys = False

    def compose(self) -> ComposeResult:
        """What the first frame shows: the timeline strip, the table, the status line and the
        footer. The panes and lines hidden at start (27 of the 36 widgets, about 0.04 s of
        CPU to compose and style) are mounted right after it (``_mount_hidden``)."""
        yield self.timeline_strip
        with Horizontal(id="main"):
            yield self.table
        yield self.status_bar
        yield KeyFooter()

    def on_mount(self) -> None:
        """The table focused and the status line shown for the first frame; after it (the
        hidden panes, the sources' threads and child processes cost CPU the first frame
        should not wait for) the rest (``_mount_hidden``), the sources and the collector
        started (the one live intake's process was started before the app was made:
        ``run_app``)."""
        app = self.app
        focus_now(self.table)
        self.update_status()
        app.call_after_refresh(self._mount_hidden)
        app.call_after_refresh(self.intake.start_sources)
        app.call_after_refresh(self.collection_policy.start)  # a collection of all start-up made

    async def _mount_hidden(self) -> None:
        """The panes and lines hidden at start mounted in their places; then the overview
        and the rules given on the command line in force, records taken in every
        ``drain_interval``, the files given opened."""
        main = self.query_one("#main", Horizontal)
        await main.mount(self.rules_pane, before=self.table)
        await main.mount_all((self.logger_pane, self.node_pane), after=self.table)
        await self.mount_all((self.query_bar, self.search_bar, self.load_bar), before=self.status_bar)
        self.ready_for_keys = True
        self.overview.start()
        self.app.set_interval(self._drain_interval, self.intake.drain_intake)
        self.filtering.apply_initial(self._initial_rules, self._initial_query)
        self.update_status()
        if self._initial_files:
            self.files.open_files(self._initial_files, robots=self._file_robots)

    _state_due = False

    def state_changed(self) -> None:
        """The console's state changed (``ConsoleContext.changed``): the status line, the
        table's hint and the footer's keys are drawn again once this turn of the event loop
        is over, however many changes it brings."""
        if not self._state_due:
            self._state_due = True
            self.context.host.call_later(self._state_drawn)

    def _state_drawn(self) -> None:
        self._state_due = False
        self.update_status()

    def update_status(self) -> None:
        """The status line, the table's hint and the footer's keys drawn now."""
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
            history=history_state(self.store),
        )
        self.status_bar.show_facts(facts)
        table.show_hint(empty_hint(facts, self.view.refiltering))
        self._refresh_footer()

    _footer_state: tuple[bool, ...] | None = None

    def _refresh_footer(self) -> None:
        """The footer's keys that come and go (the commands' ``applies``) follow the console's
        state when it changes (paused, a load ends, filtering is done), not only when the
        focus moves."""
        if self.commands.state() != self._footer_state:
            self.refresh_bindings()

    def refresh_bindings(self) -> None:
        # Whoever asks (this screen, or Textual when the focus moves), the footer is drawn
        # from the commands' states of now: a change after it is one to draw again.
        commands: CommandTable | None = getattr(self, "commands", None)
        if commands is not None:
            self._footer_state = commands.state()
        super().refresh_bindings()

    # -- what the widgets say -----------------------------------------------------------------------

    @on(QueryBar.Closed)
    @on(SidePane.Leave)
    @on(TimelineStrip.Leave)
    def _table_again(self) -> None:
        """A line, a pane or the timeline let go of the keys: the table takes them again."""
        focus_now(self.table)

    def on_log_table_state_changed(self, _message: LogTable.StateChanged) -> None:
        self.state_changed()  # the footer's Pause or Resume too
        self.overview.show(force=True)

    def on_log_table_top_reached(self, _message: LogTable.TopReached) -> None:
        self.warehouse.top_reached()

    def on_log_table_row_activated(self, message: LogTable.RowActivated) -> None:
        self.table_control.open_detail(message.seq)

    def on_query_bar_applied(self, message: QueryBar.Applied) -> None:
        self.filtering.query_applied(message)

    def on_rules_pane_changed(self, message: RulesPane.Changed) -> None:
        self.filtering.apply_rules(message.rules)

    def on_rules_pane_edit_requested(self, message: RulesPane.EditRequested) -> None:
        self.filtering.edit_rule(message.index)

    def on_rules_pane_file_requested(self, message: RulesPane.FileRequested) -> None:
        if message.save:
            self.filtering.ask_save()
        else:
            self.filtering.open_rules()

    def on_node_pane_toggle(self, message: NodePane.Toggle) -> None:
        self.toggles.node_panel_toggle(message)

    def on_logger_pane_temporary_requested(self, message: LoggerPane.TemporaryRequested) -> None:
        self.panes.ask_temporary_level(message)

    def on_timeline_strip_jump(self, message: TimelineStrip.Jump) -> None:
        self.overview.show_seq(message.seq)

    def on_search_bar_changed(self, message: SearchBar.Changed) -> None:
        self.searching.search_line_changed(message)

    def on_search_bar_done(self, message: SearchBar.Done) -> None:
        self.searching.search_line_done(message)
