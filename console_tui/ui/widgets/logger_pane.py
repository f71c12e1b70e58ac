"""The logger levels pane, beside the table: the graph's nodes, a node's loggers and their levels.

The pane draws a ``LoggerPaneState`` (the model of what it shows) and turns keys into requests
(``logger_requests.py``: the calls of the ``LoggerControl`` and their books). With a
control, the pane keeps its state fed (nodes as the graph changes, levels as they are read,
temporary levels as they run); tests may feed it through ``show_*`` and ``select_node`` for a
fixed picture. Every service call runs on the control's thread: its end comes back as a
message, so the screen never waits for a node. For a temporary level the pane posts
``TemporaryRequested``: the app asks for the level and time.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.message import Message
from textual.timer import Timer
from textual.widget import Widget
from textual.widgets import Input, OptionList, Static

from ...control.events import LoggerEvent, NodesChanged
from ...model.levels import MESSAGE_SEVERITIES
from ...model.loggers.logger_levels import GraphNode, LoggerRow, TemporaryLevel
from ..keys import Hint, hint_line
from ..plain import plain
from .level_bar import TEMPORARY, LevelBar
from .logger_lists import GraphNodeList, LoggerList
from .logger_requests import CallEnded, LoggerRequests
from .side_pane import RightPane

if TYPE_CHECKING:
    from ...control.control_thread import LoggerControl

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


class LoggerPane(RightPane):
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
        & > GraphNodeList { height: auto; max-height: 40%; }
        & > LoggerList { height: 1fr; min-height: 3; }
        & > GraphNodeList:focus, & > LoggerList:focus { background-tint: $foreground 5%; }
        & > #logger-heading { height: 1; margin-top: 1; text-style: bold; color: $text-primary; }
        & > #logger-notice { height: auto; max-height: 6; color: $text-muted; }
        & > #logger-notice.-error { color: $text-error; }
        & > LevelBar { height: auto; color: $text-accent; }
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

    @dataclass
    class ControlEvent(Message):
        """An event of the ``LoggerControl``, or the end of a call (posted from its thread)."""

        event: LoggerEvent | CallEnded

        def can_replace(self, message: Message) -> bool:
            # A burst of graph changes: only the newest node list matters.
            return (
                isinstance(message, LoggerPane.ControlEvent)
                and isinstance(self.event, NodesChanged)
                and isinstance(message.event, NodesChanged)
            )

    @dataclass
    class TemporaryRequested(Message):
        """``t`` on a logger: ask for a level and a time, then call ``set_temporary``."""

        pane: LoggerPane
        fqn: str
        logger: str

    def __init__(
        self,
        control: LoggerControl | None = None,
        *,
        seen_loggers: Collection[str] = (),
        clock: Callable[[], float] | None = None,
        id: str | None = "logger-pane",
    ) -> None:
        super().__init__(id=id)
        self.clock = control.clock if control is not None else clock
        self.requests = LoggerRequests(control, self._from_control_thread, seen_loggers=seen_loggers)
        self.state = self.requests.state
        self._ticker: Timer | None = None
        #: A row's logger and robot asked for (``L``) before the graph was known.
        self._pending_logger: tuple[str, str] | None = None
        self.node_list = GraphNodeList(id="logger-nodes", compact=True)
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
        yield Static(hint_line(self.app, self.BINDINGS, _HINTS), id="logger-keys", classes="pane-keys")

    def on_mount(self) -> None:
        if self.requests.control is not None:
            self.requests.control.watch_graph(self.is_open)
            self.requests.listen()
            self.show_nodes(self.requests.control.nodes)
        self._render_all()

    def when_opened(self) -> None:
        if self.requests.control is not None:
            self.requests.control.start()  # the first opening starts it (the app joins the graph then)
            self.requests.control.watch_graph(True)
        if self.requests.opened():
            self._render_nodes()
        self._render_notice()  # the control may have just started looking for the graph
        if self.selected is None and self.node_list.option_count:
            self.node_list.highlighted = 0
        elif self.selected is not None:
            self.read_levels(self.selected)
        self._update_ticker()

    def when_closed(self) -> None:
        if self.requests.control is not None:
            self.requests.control.watch_graph(False)  # the master is asked only while someone looks
        self._update_ticker()

    def focus_target(self) -> Widget:
        return self.logger_list if self.selected and self.logger_list.option_count else self.node_list

    # -- what it shows ----------------------------------------------------------------------------

    @property
    def selected(self) -> str | None:
        return self.state.selected

    @property
    def nodes(self) -> tuple[GraphNode, ...]:
        return self.state.nodes

    @property
    def highlighted_logger(self) -> str | None:
        return self.logger_list.highlighted_logger

    def rows(self) -> list[LoggerRow]:
        """The selected node's logger rows, as shown."""
        return self.state.rows()

    def show_nodes(self, nodes: Sequence[GraphNode], checking: Collection[str] | None = None) -> None:
        """The graph's nodes; ``checking`` names those whose logger services may yet appear."""
        had_selection = self.selected is not None
        self.requests.set_nodes(nodes, checking)
        self._render_nodes()
        pending, self._pending_logger = self._pending_logger, None
        if pending is not None and self.is_open and self.state.nodes and self.open_for_logger(*pending):
            pass  # the row's node, asked for before the graph came
        elif not had_selection and self.is_open and self.state.nodes:
            self.node_list.highlighted = 0  # the first nodes since the pane opened: show one
        self._render_loggers()
        self._update_ticker()

    def select_node(self, fqn: str, logger: str | None = None) -> bool:
        """Show ``fqn``'s loggers (reading their levels), with ``logger`` highlighted."""
        changed = self.requests.select(fqn, logger)
        if changed is None:
            return False
        if changed:
            with self.node_list.prevent(OptionList.OptionHighlighted):
                self.node_list.highlighted = self.node_list.get_option_index(fqn)
        node = self.state.selected_node
        own = node.logger_name if node is not None else None
        self._render_loggers(highlight=logger if logger is not None else (None if not changed else own))
        return True

    def show_levels(self, fqn: str, levels: Mapping[str, int]) -> None:
        """Levels read from (or just set on) node ``fqn``."""
        if self.state.set_levels(fqn, levels):
            self._render_loggers()

    def show_temporaries(self, entries: Sequence[TemporaryLevel]) -> None:
        self.state.temporaries = tuple(entries)
        self._render_loggers()
        self._update_ticker()

    def show_failure(self, text: str) -> None:
        """A failed call: said in the pane and as a notification."""
        self.state.say(text, error=True)
        self._render_notice()
        self.app.notify(text, title="Logger levels", severity="error", timeout=8, markup=False)

    def open_for_logger(self, logger: str, robot: str = "") -> bool:
        """Open on the node whose messages carry this logger name (a table row's node, on the
        row's robot in a fleet)."""
        self.open(focus=False)
        node = self.state.node_logging_as(logger, robot)
        if node is None:
            # No graph yet (a ROS 1 master is asked only once the pane is open): when it comes.
            self._pending_logger = (logger, robot) if not self.state.nodes else None
            self._render_notice()  # says so
            self.node_list.focus()
            return False
        self._pending_logger = None
        self.select_node(node.fqn, None if logger == node.path else logger)
        self.logger_list.focus()
        return True

    # -- service calls (``LoggerRequests`` makes them and keeps their books) -----------------------

    def read_levels(self, fqn: str, *, asked: bool = False) -> None:
        """Read ``fqn``'s levels; where they are read only when asked (ROS 1), only when ``asked``."""
        self.requests.read_levels(fqn, asked=asked)
        self._render_heading()

    def set_temporary(self, fqn: str, logger: str, level: int, seconds: float) -> None:
        """Set a temporary level (the app's answer to ``TemporaryRequested``)."""
        self.requests.set_temporary(fqn, logger, level, seconds)
        self._render_status()

    def _from_control_thread(self, event: LoggerEvent | CallEnded) -> None:
        self.post_message(self.ControlEvent(event))

    def on_logger_pane_control_event(self, message: ControlEvent) -> None:
        message.stop()
        event = message.event
        if isinstance(event, NodesChanged):
            self.show_nodes(event.nodes)
            return
        failure = self.requests.finish(event)  # a call or a temporary level ended
        self._render_loggers()
        self._update_ticker()
        if failure is not None:
            self.show_failure(failure)

    # -- keys and clicks -------------------------------------------------------------------------

    def _target(self) -> tuple[str, str] | None:
        target = self.state.target(self.highlighted_logger)
        if target is None:
            self._render_loggers()  # says why
        return target

    def action_set_level(self, level: int) -> None:
        target = self._target()
        if target is not None:
            self.requests.set_level(*target, level)
            self._render_status()

    def action_temporary(self) -> None:
        target = self._target()
        if target is not None:
            self.post_message(self.TemporaryRequested(self, *target))

    def action_end_temporary(self) -> None:
        target = self._target()
        if target is not None:
            self.requests.end_temporary(*target)
            self._render_status()

    def action_add_logger(self) -> None:
        self.name_input.focus()

    def action_refresh(self) -> None:
        self.requests.reread()
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
        if self.selected is not None and self.state.reads_when_asked(self.selected):
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
        name = self.requests.add_logger(message.value)
        if name is None:
            return
        self.name_input.value = ""
        self._render_loggers(highlight=name)
        self.logger_list.focus()

    # -- drawing ------------------------------------------------------------------------------

    def _render_all(self) -> None:
        self._render_nodes()
        self._render_loggers()

    def _render_nodes(self) -> None:
        self.node_list.show(self.state.nodes, self.state.checking, self.state.selected)
        if not self.state.nodes:
            self._render_heading()

    def _render_loggers(self, highlight: str | None = None) -> None:
        node = self.state.selected_node
        own = node.logger_name if node is not None else ""
        now = self.clock() if self.clock is not None else 0.0
        self.logger_list.show(self.state.rows(), own, now, highlight)
        self._render_heading()
        self._render_notice()

    def _render_status(self) -> None:
        """The heading (a call under way) and the notice."""
        self._render_heading()
        self._render_notice()

    def _render_heading(self) -> None:
        self.heading.update(plain(self.state.heading(), no_wrap=True, overflow="ellipsis"))

    def _render_notice(self) -> None:
        text, error = self.state.notice_text(
            self.requests.problem,
            hint_line(self.app, [*OptionList.BINDINGS, *self.BINDINGS], _READ_HINTS),
            looking=self.requests.looking,
        )
        self.notice_line.update(plain(text, lines=True))
        self.notice_line.set_class(error, "-error")

    def _render_checking(self) -> None:
        self._render_nodes()
        self._render_notice()

    # -- keeping up -----------------------------------------------------------------------------

    def _update_ticker(self) -> None:
        """A 1 s tick while the pane is open: countdowns, "checking" marks, new child loggers,
        the notice while no node is known."""
        if self.is_open and self.is_mounted and self._ticker is None:
            self._ticker = self.set_interval(TICK_S, self._tick)
        elif not self.is_open and self._ticker is not None:
            self._ticker.stop()
            self._ticker = None

    def _tick(self) -> None:
        requests = self.requests
        if (requests.problem and requests.problem not in str(self.notice_line.content)) or not self.state.nodes:
            self._render_notice()  # a new problem, or still looking for the graph's nodes
        if requests.take_temporaries():
            self._render_loggers()
        if self.state.checking and requests.refresh_checking():
            self._render_checking()
        if requests.new_child_loggers() or self.state.counting_down():
            self._render_loggers()  # the new loggers, or the countdown
