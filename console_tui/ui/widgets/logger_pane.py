"""The logger levels pane, beside the table: the graph's nodes, a node's loggers and their levels.

The pane draws a ``LoggerView`` (the model of what it shows) and turns keys into calls of the
``LoggerControl``. With a control, the pane feeds the view itself (nodes as the graph changes,
levels as they are read, temporary levels as they run); tests may feed it through ``show_*``
and ``select_node`` for a fixed picture. Every service call runs on the control's thread: its
future's outcome comes back as a message, so the screen never waits for a node. For a
temporary level the pane posts ``TemporaryRequested``: the app asks for the level and time.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from concurrent.futures import Future
from typing import TYPE_CHECKING, Any

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.message import Message
from textual.timer import Timer
from textual.widget import Widget
from textual.widgets import Input, OptionList, Static

from ...model.levels import MESSAGE_SEVERITIES
from ...model.logger_levels import ENABLE_LOGGER_SERVICE_HINT, GraphNode, LoggerRow, TemporaryLevel, node_of_logger
from ...model.logger_view import NO_ROS_TEXT, LoggerView, level_word, shown_logger
from ..keys import Hint, hint_line
from ..plain import plain
from .level_bar import TEMPORARY, LevelBar
from .logger_lists import LoggerList, NodeList
from .side_pane import SidePane

if TYPE_CHECKING:
    from ...sources.logger_control import LoggerControl, LoggerEvent

__all__ = ["NO_ROS_TEXT", "LoggerPane"]

TICK_S = 1.0

_HINTS: list[Hint] = [
    (tuple(f"set_level({int(s)})" for s in MESSAGE_SEVERITIES), "level"),
    ("set_level(0)", "inherit"),
    ("temporary", "temporary"),
    ("end_temporary", "end it"),
    ("add_logger", "add"),
    ("refresh", "read"),
    ("leave", "table"),
]


#: Where levels are read only when asked (ROS 1): how to ask.
_READ_HINTS: list[Hint] = [(("select", "refresh"), "read its loggers"), ("add_logger", "set one by name")]


class LoggerPane(SidePane):
    """Nodes, then the selected node's loggers; keys set the highlighted logger's level.

    | Key(s) | Description |
    | :- | :- |
    | d, 1 / i, 2 / w, 3 / e, 4 / f, 5 | Set DEBUG / INFO / WARN / ERROR / FATAL. |
    | u, 0 | Unset: the logger inherits its level. |
    | t | Temporary level (the app asks which, and for how long). |
    | x | End the temporary level now. |
    | a, plus | Add a logger by name. |
    | r | Read the levels again. |
    | left / right | To the nodes / to the loggers. |
    | escape | Back to the table. |
    """

    DEFAULT_CSS = """
    LoggerPane {
        width: 46;
        max-width: 50%;
        height: 100%;
        background: $surface;
        border-left: vkey $border-blurred;
        padding: 0 0 0 1;
        &:focus-within { border-left: vkey $border; }
        & > .pane-title { text-style: bold; color: $text-primary; height: 1; }
        & > NodeList { height: auto; max-height: 40%; }
        & > LoggerList { height: 1fr; min-height: 3; }
        & > NodeList:focus, & > LoggerList:focus { background-tint: $foreground 5%; }
        & > #logger-heading { height: 1; margin-top: 1; text-style: bold; color: $text-primary; }
        & > #logger-notice { height: auto; max-height: 6; color: $text-muted; }
        & > #logger-notice.-error { color: $text-error; }
        & > LevelBar { height: auto; color: $text-accent; }
        & > Input { margin: 0; }
        & > #logger-keys { height: auto; color: $text-muted; }
    }
    """

    BINDINGS = [
        Binding("d,1", "set_level(10)", "Set DEBUG", show=False, id="loggers.debug"),
        Binding("i,2", "set_level(20)", "Set INFO", show=False, id="loggers.info"),
        Binding("w,3", "set_level(30)", "Set WARN", show=False, id="loggers.warn"),
        Binding("e,4", "set_level(40)", "Set ERROR", show=False, id="loggers.error"),
        Binding("f,5", "set_level(50)", "Set FATAL", show=False, id="loggers.fatal"),
        Binding("u,0", "set_level(0)", "Unset: inherit the level", show=False, id="loggers.unset"),
        Binding("t", "temporary", "Temporary level", id="loggers.temporary"),
        Binding("x", "end_temporary", "End the temporary level now", show=False, id="loggers.end_temporary"),
        Binding("a,plus", "add_logger", "Add a logger by name", show=False, id="loggers.add"),
        Binding("r", "refresh", "Read the levels again", show=False, id="loggers.read"),
        Binding("left", "focus_nodes", "To the nodes", show=False, id="loggers.to_nodes"),
        Binding("right", "focus_loggers", "To the loggers", show=False, id="loggers.to_loggers"),
        Binding("escape", "leave", "Back to the table", show=False, id="loggers.leave"),
    ]

    class ControlEvent(Message):
        """An event of the ``LoggerControl`` (posted from its thread)."""

        def __init__(self, event: LoggerEvent) -> None:
            super().__init__()
            self.event = event

        def can_replace(self, message: Message) -> bool:
            # A burst of graph changes: only the newest node list matters.
            from ...sources.logger_control import NodesChanged

            return (
                isinstance(message, LoggerPane.ControlEvent)
                and isinstance(self.event, NodesChanged)
                and isinstance(message.event, NodesChanged)
            )

    class CallDone(Message):
        """A service call finished (its future is done); ``then`` takes its result."""

        def __init__(self, future: Future[Any], fqn: str, what: str, then: Callable[[Any], None]) -> None:
            super().__init__()
            self.future = future
            self.fqn = fqn
            self.what = what
            self.then = then

    class TemporaryRequested(Message):
        """``t`` on a logger: ask for a level and a time, then call ``set_temporary``."""

        def __init__(self, pane: LoggerPane, fqn: str, logger: str) -> None:
            super().__init__()
            self.pane = pane
            self.fqn = fqn
            self.logger = logger

    def __init__(
        self,
        control: LoggerControl | None = None,
        *,
        seen_loggers: Collection[str] = (),
        clock: Callable[[], float] | None = None,
        id: str | None = "logger-pane",
    ) -> None:
        super().__init__(id=id)
        self.control = control
        #: Logger names seen in records (the store's node column): where child loggers come from.
        self.seen_loggers = seen_loggers
        self.clock = control.clock if control is not None else clock
        # Without a control (files only, or a test feeding the pane) nodes are ROS 2's.
        self.view = LoggerView(
            has_ros=control is not None,
            no_services_hint=control.no_services_hint if control is not None else ENABLE_LOGGER_SERVICE_HINT,
            lists_loggers=control is not None and control.lists_loggers,
            read_when_asked=control is not None and control.read_when_asked,
        )
        self._ticker: Timer | None = None
        self.node_list = NodeList(id="logger-nodes", compact=True)
        self.logger_list = LoggerList(id="logger-levels", compact=True)
        self.name_input = Input(placeholder="add a logger: type its name, Enter", id="logger-name", compact=True)
        self.heading = Static("Loggers", id="logger-heading")
        self.notice_line = Static("", id="logger-notice")

    # -- layout ---------------------------------------------------------------------------------

    def compose(self) -> ComposeResult:
        yield Static("Logger levels · nodes", classes="pane-title")
        yield self.node_list
        yield self.heading
        yield self.logger_list
        yield self.notice_line
        yield LevelBar(id="logger-level-bar")
        yield self.name_input
        yield Static(hint_line(self.app, self.BINDINGS, _HINTS), id="logger-keys")

    def on_mount(self) -> None:
        control = self.control
        if control is not None:
            control.subscribe(self._from_control_thread)
            self.show_nodes(control.nodes)
        self._render_all()

    def when_opened(self) -> None:
        self.view.note_seen(self.seen_loggers)
        self._refresh_checking()
        if self.selected is None and self.node_list.option_count:
            self.node_list.highlighted = 0
        elif self.selected is not None:
            self.read_levels(self.selected)
        self._update_ticker()

    def when_closed(self) -> None:
        self._update_ticker()

    def focus_target(self) -> Widget:
        return self.logger_list if self.selected and self.logger_list.option_count else self.node_list

    # -- what it shows ----------------------------------------------------------------------------

    @property
    def selected(self) -> str | None:
        return self.view.selected

    @property
    def nodes(self) -> tuple[GraphNode, ...]:
        return self.view.nodes

    @property
    def highlighted_logger(self) -> str | None:
        return self.logger_list.highlighted_logger

    def rows(self) -> list[LoggerRow]:
        """The selected node's logger rows, as shown."""
        return self.view.rows()

    def show_nodes(self, nodes: Sequence[GraphNode], checking: Collection[str] | None = None) -> None:
        """The graph's nodes; ``checking`` names those whose logger services may yet appear."""
        view = self.view
        had_selection = view.selected is not None
        if checking is None:
            checking = self._checking_now(nodes)
        services_appeared = view.set_nodes(nodes, checking)
        view.note_seen(self.seen_loggers, force=True)
        self._render_nodes()
        if not had_selection and self.is_open and view.nodes:
            self.node_list.highlighted = 0  # the first nodes since the pane opened: show one
        elif services_appeared and view.selected is not None:
            self.read_levels(view.selected)
        self._render_loggers()
        self._update_ticker()

    def select_node(self, fqn: str, logger: str | None = None) -> bool:
        """Show ``fqn``'s loggers (reading their levels), with ``logger`` highlighted."""
        view = self.view
        changed = view.select(fqn, logger)
        if changed is None:
            return False
        view.note_seen(self.seen_loggers, force=True)
        if changed:
            with self.node_list.prevent(OptionList.OptionHighlighted):
                self.node_list.highlighted = self.node_list.get_option_index(fqn)
        node = view.selected_node
        own = node.logger_name if node is not None else None
        self._render_loggers(highlight=logger if logger is not None else (None if not changed else own))
        if changed or logger is not None:
            self.read_levels(fqn)
        return True

    def show_levels(self, fqn: str, levels: Mapping[str, int]) -> None:
        """Levels read from (or just set on) node ``fqn``."""
        if self.view.set_levels(fqn, levels):
            self._render_loggers()

    def show_temporaries(self, entries: Sequence[TemporaryLevel]) -> None:
        self.view.temporaries = tuple(entries)
        self._render_loggers()
        self._update_ticker()

    def show_failure(self, text: str) -> None:
        """A failed call: said in the pane and as a notification."""
        self._say(text, error=True)
        self.app.notify(text, title="Logger levels", severity="error", timeout=8, markup=False)

    def open_for_logger(self, logger: str) -> bool:
        """Open on the node whose messages carry this logger name (a table row's node)."""
        self.open(focus=False)
        node = node_of_logger(logger, self.nodes)
        if node is None:
            self._say(f"No node in the ROS graph logs as {logger!r} (it may have exited)", error=True)
            self.node_list.focus()
            return False
        self.select_node(node.fqn, None if logger == node.fqn else logger)
        self.logger_list.focus()
        return True

    # -- service calls ------------------------------------------------------------------------

    def read_levels(self, fqn: str, *, asked: bool = False) -> None:
        """Read ``fqn``'s levels; where they are read only when asked (ROS 1), only when ``asked``."""
        names = self.view.names_to_read(fqn)
        if self.control is None or names is None or (self.view.read_when_asked and not asked):
            return
        self._call(
            self.control.get_levels(fqn, names), fqn, "read the levels", lambda levels: self.show_levels(fqn, levels)
        )

    def set_level(self, fqn: str, logger: str, level: int) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(levels: Mapping[str, int]) -> None:
            self.view.level_set(fqn, logger, level, levels)
            self.show_temporaries(control.temporaries())
            self.read_levels(fqn)

        what = f"set {shown_logger(logger)} to {level_word(level)}"
        self._call(control.set_level(fqn, logger, level), fqn, what, done)

    def set_temporary(self, fqn: str, logger: str, level: int, seconds: float) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(entry: TemporaryLevel) -> None:
            self.view.temporary_set(fqn, entry, seconds)
            self.show_temporaries(control.temporaries())
            self.read_levels(fqn)

        what = f"set {shown_logger(logger)} to {level_word(level)} for {seconds:g} s"
        self._call(control.set_temporary(fqn, logger, level, seconds), fqn, what, done)

    def end_temporary(self, fqn: str, logger: str) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(_levels: Mapping[str, int]) -> None:
            self.view.say(f"{shown_logger(logger)}: temporary level ended")
            self.show_temporaries(control.temporaries())
            self.read_levels(fqn)

        self._call(control.end_temporary(fqn, logger), fqn, f"end the temporary level of {shown_logger(logger)}", done)

    def _usable_control(self) -> LoggerControl | None:
        if self.control is None:
            self._say(NO_ROS_TEXT, error=True)
        return self.control

    def _call(self, future: Future[Any], fqn: str, what: str, then: Callable[[Any], None]) -> None:
        self.view.call_started(fqn)
        self._render_heading()
        future.add_done_callback(lambda done: self.post_message(self.CallDone(done, fqn, what, then)))

    def on_logger_pane_call_done(self, message: CallDone) -> None:
        message.stop()
        self.view.call_ended(message.fqn)
        self._render_heading()
        error = message.future.exception()
        if error is None:
            message.then(message.future.result())
        else:
            self.show_failure(f"Could not {message.what}: {error}")

    def _from_control_thread(self, event: LoggerEvent) -> None:
        self.post_message(self.ControlEvent(event))

    def on_logger_pane_control_event(self, message: ControlEvent) -> None:
        from ...sources.logger_control import NodesChanged, TemporaryEnded

        message.stop()
        event = message.event
        if isinstance(event, NodesChanged):
            self.show_nodes(event.nodes)
        elif isinstance(event, TemporaryEnded) and self.control is not None:
            failure = self.view.temporary_ended(event.entry, event.error)
            self.show_temporaries(self.control.temporaries())
            if failure is not None:
                self.show_failure(failure)
            self.read_levels(event.entry.node)

    # -- keys and clicks -------------------------------------------------------------------------

    def _target(self) -> tuple[str, str] | None:
        target = self.view.target(self.highlighted_logger)
        if target is None:
            self._render_loggers()  # says why
        return target

    def action_set_level(self, level: int) -> None:
        target = self._target()
        if target is not None:
            self.set_level(*target, level)

    def action_temporary(self) -> None:
        target = self._target()
        if target is not None:
            self.post_message(self.TemporaryRequested(self, *target))

    def action_end_temporary(self) -> None:
        target = self._target()
        if target is not None:
            self.end_temporary(*target)

    def action_add_logger(self) -> None:
        self.name_input.focus()

    def action_refresh(self) -> None:
        self.view.note_seen(self.seen_loggers, force=True)
        if self.selected is not None:
            self.read_levels(self.selected, asked=True)
        self._render_all()

    def action_focus_nodes(self) -> None:
        self.node_list.focus()

    def action_focus_loggers(self) -> None:
        self.logger_list.focus()

    def action_leave(self) -> None:
        if self.name_input.has_focus:
            self.name_input.value = ""
            self.logger_list.focus()
        else:
            super().action_leave()

    @on(OptionList.OptionHighlighted, "#logger-nodes")
    def _node_highlighted(self, message: OptionList.OptionHighlighted) -> None:
        message.stop()
        # Only the newest highlight counts: one moved since the message was sent is stale.
        if message.option.id is not None and message.option_index == self.node_list.highlighted:
            self.select_node(message.option.id)

    @on(OptionList.OptionSelected, "#logger-nodes")
    def _node_chosen(self, message: OptionList.OptionSelected) -> None:
        message.stop()
        if self.selected is not None and self.view.read_when_asked:
            self.read_levels(self.selected, asked=True)  # Enter opens the node: its loggers are read
        self.logger_list.focus()

    @on(OptionList.OptionSelected, "#logger-levels")
    def _logger_chosen(self, message: OptionList.OptionSelected) -> None:
        message.stop()  # Enter or a click just highlights: levels come from keys and the level bar

    @on(LevelBar.Chosen)
    def _level_clicked(self, message: LevelBar.Chosen) -> None:
        message.stop()
        if message.level == TEMPORARY:
            self.action_temporary()
        else:
            self.action_set_level(message.level)

    @on(Input.Submitted, "#logger-name")
    def _name_typed(self, message: Input.Submitted) -> None:
        message.stop()
        name = self.view.add_logger(message.value)
        if name is None or self.selected is None:
            return
        self.name_input.value = ""
        self._render_loggers(highlight=name)
        self.read_levels(self.selected)
        self.logger_list.focus()

    # -- drawing ------------------------------------------------------------------------------

    def _render_all(self) -> None:
        self._render_nodes()
        self._render_loggers()

    def _render_nodes(self) -> None:
        self.node_list.show(self.view.nodes, self.view.checking, self.view.selected)
        if not self.view.nodes:
            self._render_heading()

    def _render_loggers(self, highlight: str | None = None) -> None:
        node = self.view.selected_node
        own = node.logger_name if node is not None else ""
        now = self.clock() if self.clock is not None else 0.0
        self.logger_list.show(self.view.rows(), own, now, highlight)
        self._render_heading()
        self._render_notice()

    def _render_heading(self) -> None:
        self.heading.update(plain(self.view.heading(), no_wrap=True, overflow="ellipsis"))

    def _render_notice(self) -> None:
        problem = self.control.problem if self.control is not None else ""
        text, error = self.view.notice_text(
            problem, hint_line(self.app, [*OptionList.BINDINGS, *self.BINDINGS], _READ_HINTS)
        )
        self.notice_line.update(plain(text, lines=True))
        self.notice_line.set_class(error, "-error")

    def _say(self, text: str, error: bool = False) -> None:
        self.view.say(text, error)
        self._render_notice()

    # -- keeping up -----------------------------------------------------------------------------

    def _checking_now(self, nodes: Sequence[GraphNode] | None = None) -> frozenset[str]:
        control = self.control
        if control is None:
            return self.view.checking
        return self.view.unsettled(control.is_settled, self.view.nodes if nodes is None else nodes)

    def _refresh_checking(self) -> None:
        checking = self._checking_now()
        if checking != self.view.checking:
            self.view.checking = checking
            self._render_nodes()
            self._render_notice()

    def _update_ticker(self) -> None:
        """A 1 s tick while the pane is open: countdowns, "checking" marks, new child loggers."""
        if self.is_open and self.is_mounted and self._ticker is None:
            self._ticker = self.set_interval(TICK_S, self._tick)
        elif not self.is_open and self._ticker is not None:
            self._ticker.stop()
            self._ticker = None

    def _tick(self) -> None:
        view = self.view
        if self.control is not None:
            if self.control.problem and self.control.problem not in str(self.notice_line.content):
                self._render_notice()
            temporaries = self.control.temporaries()
            if temporaries != view.temporaries:
                view.temporaries = temporaries
                self._render_loggers()
        if view.checking:
            self._refresh_checking()
        if view.note_seen(self.seen_loggers):
            self._render_loggers()
            if self.selected is not None:
                self.read_levels(self.selected)
        elif view.counting_down():
            self._render_loggers()  # the countdown
