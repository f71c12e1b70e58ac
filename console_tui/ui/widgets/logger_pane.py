"""The logger levels pane, beside the table: the graph's nodes, a node's loggers and their levels.

What it shows is UI state, changed through its ``show_*`` and ``select_node`` methods. With a
``LoggerControl`` the pane feeds them itself (nodes as the graph changes, levels as they are
read, temporary levels as they run); tests may feed them directly for a fixed picture. Every
service call runs on the control's thread: its future's outcome comes back as a message, so
the screen never waits for a node.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from concurrent.futures import Future
from typing import TYPE_CHECKING, Any

from rich.table import Table
from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.message import Message
from textual.timer import Timer
from textual.widget import Widget
from textual.widgets import Input, OptionList, Static
from textual.widgets.option_list import Option

from ...model.levels import MESSAGE_SEVERITIES, Severity, severity_name
from ...model.logger_levels import (
    DEFAULT_LOGGER,
    ENABLE_LOGGER_SERVICE_HINT,
    GraphNode,
    LoggerRow,
    LoggerSource,
    NodeLoggers,
    TemporaryLevel,
    format_remaining,
    node_of_logger,
)
from ..keys import Hint, hint_line
from ..plain import plain
from .side_pane import SidePane

if TYPE_CHECKING:
    from ...sources.logger_control import LoggerControl

#: How long ``t`` sets a temporary level for unless told otherwise.
DEFAULT_TEMPORARY_S = 30.0
TICK_S = 1.0
#: What the pane says when this run has no live ROS (files only).
NO_ROS_TEXT = "No live ROS in this console (files only): logger levels cannot be read or set."

_HINTS: list[Hint] = [
    (tuple(f"set_level({int(s)})" for s in MESSAGE_SEVERITIES), "level"),
    ("set_level(0)", "inherit"),
    ("temporary", "temporary"),
    ("end_temporary", "end it"),
    ("add_logger", "add"),
    ("refresh", "read"),
    ("leave", "table"),
]

_LEVEL_STYLE = {10: "dim", 20: "green", 30: "yellow", 40: "red", 50: "bold red"}


def logger_label(row: LoggerRow, own: str) -> str:
    """How a logger's name reads in the list: children relative to the node's logger."""
    if row.source is LoggerSource.DEFAULT:
        return '"" (default)'
    if row.source is LoggerSource.CHILD and row.name.startswith(own + "."):
        return "  ." + row.name[len(own) + 1 :]
    return row.name


def level_cell(row: LoggerRow, now: float) -> Text:
    """A logger's level: ``DEBUG``, ``inherited (INFO)``, ``?``, or ``DEBUG 25s`` while temporary."""
    if row.temporary is not None:
        temporary = row.temporary
        text = Text(severity_name(temporary.level), style=_LEVEL_STYLE.get(temporary.level, ""))
        text.append(" for ")
        text.append(format_remaining(temporary.remaining(now)), style="bold")
        return text
    if row.level == Severity.UNSET:
        return Text(row.level_text, style="italic dim")
    return Text(row.level_text, style=_LEVEL_STYLE.get(row.level or 0, "dim"))


def _two_columns(left: Text | str, right: Text | str) -> Table:
    grid = Table.grid(expand=True)
    grid.add_column(ratio=1, no_wrap=True, overflow="ellipsis")
    grid.add_column(no_wrap=True, justify="right")
    grid.add_row(left, right)
    return grid


class NodeList(OptionList):
    """The graph's nodes; the highlighted one is the pane's selected node."""


class LoggerList(OptionList):
    """The selected node's loggers; level keys act on the highlighted one."""


class LevelBar(Static):
    """Clickable level names: a click sets the highlighted logger's level."""

    class Chosen(Message):
        def __init__(self, level: int) -> None:
            super().__init__()
            self.level = level

    def on_mount(self) -> None:
        parts = [f"[@click=choose({int(s)})]{s.name}[/]" for s in MESSAGE_SEVERITIES]
        parts.append(f"[@click=choose({int(Severity.UNSET)})]unset[/]")
        parts.append("[@click=temporary]temporary[/]")
        self.update(" ".join(parts))

    def action_choose(self, level: int) -> None:
        self.post_message(self.Chosen(level))

    def action_temporary(self) -> None:
        self.post_message(self.Chosen(-1))


class LoggerPane(SidePane):
    """Nodes, then the selected node's loggers; keys set the highlighted logger's level."""

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

        def __init__(self, event: Any) -> None:
            super().__init__()
            self.event = event

    class CallDone(Message):
        """A service call finished (its future is done); ``then`` takes its result."""

        def __init__(self, future: Future, fqn: str, what: str, then: Callable[[Any], None]) -> None:
            super().__init__()
            self.future = future
            self.fqn = fqn
            self.what = what
            self.then = then

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
        self.nodes: tuple[GraphNode, ...] = ()
        self.checking: frozenset[str] = frozenset()
        self.selected: str | None = None
        self.loggers: dict[str, NodeLoggers] = {}
        self.temporaries: tuple[TemporaryLevel, ...] = ()
        self.pending: dict[str, int] = {}
        self.notice = ""
        self.notice_is_error = False
        self._seen_count = -1
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
        self._note_seen_loggers()
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

    # -- UI state -----------------------------------------------------------------------------

    def show_nodes(self, nodes: Sequence[GraphNode], checking: Collection[str] | None = None) -> None:
        """The graph's nodes; ``checking`` names those whose logger services may yet appear."""
        before = {node.fqn: node for node in self.nodes}
        self.nodes = tuple(nodes)
        self.checking = frozenset(checking) if checking is not None else self._checking_now()
        selected = self.selected
        if selected is not None and selected not in {node.fqn for node in self.nodes}:
            self.selected = None
            self._say(f"{selected} left the ROS graph")
        self._note_seen_loggers(force=True)
        self._render_nodes()
        if selected is None and self.is_open and self.nodes:
            self.node_list.highlighted = 0  # the first nodes since the pane opened: show one
        elif self.selected is not None:
            node = self.node(self.selected)
            old = before.get(self.selected)
            if node is not None and node.has_logger_services and not (old and old.has_logger_services):
                self.read_levels(node.fqn)  # its services just showed up
        self._render_loggers()
        self._update_ticker()

    def select_node(self, fqn: str, logger: str | None = None) -> bool:
        """Show ``fqn``'s loggers (reading their levels), with ``logger`` highlighted."""
        node = self.node(fqn)
        if node is None:
            return False
        changed = fqn != self.selected
        self.selected = fqn
        loggers = self._loggers_of(node)
        self._note_seen_loggers(force=True)
        if logger is not None and logger not in loggers.names():
            loggers.add_typed(logger)
        if changed:
            self.notice = ""
            with self.node_list.prevent(OptionList.OptionHighlighted):
                self.node_list.highlighted = self.node_list.get_option_index(fqn)
        self._render_loggers(highlight=logger if logger is not None else (None if not changed else loggers.own))
        if changed or logger is not None:
            self.read_levels(fqn)
        return True

    def show_levels(self, fqn: str, levels: Mapping[str, int]) -> None:
        """Levels read from (or just set on) node ``fqn``."""
        node = self.node(fqn)
        if node is None:
            return
        self._loggers_of(node).update_levels(levels)
        if fqn == self.selected:
            self._render_loggers()

    def show_temporaries(self, entries: Sequence[TemporaryLevel]) -> None:
        self.temporaries = tuple(entries)
        self._render_loggers()
        self._update_ticker()

    def show_failure(self, text: str) -> None:
        """A failed call: said in the pane and as a notification."""
        self._say(text, error=True)
        self.app.notify(text, title="Logger levels", severity="error", timeout=8, markup=False)

    def node(self, fqn: str) -> GraphNode | None:
        return next((node for node in self.nodes if node.fqn == fqn), None)

    def rows(self) -> list[LoggerRow]:
        """The selected node's logger rows, as shown."""
        node = self.node(self.selected) if self.selected else None
        if node is None or not node.has_logger_services:
            return []
        return self._loggers_of(node).rows(self.temporaries)

    @property
    def highlighted_logger(self) -> str | None:
        option = self.logger_list.highlighted_option
        return None if option is None else _logger_of_option(option)

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
        """Read ``fqn``'s levels; with a control that reads only when asked (ROS 1), only when ``asked``."""
        node = self.node(fqn)
        control = self.control
        if control is None or node is None or not node.has_logger_services:
            return
        if control.read_when_asked and not asked:
            return
        names = self._loggers_of(node).names_to_read()
        self._call(control.get_levels(fqn, names), fqn, "read the levels", lambda levels: self.show_levels(fqn, levels))

    def set_level(self, fqn: str, logger: str, level: int) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(levels: Mapping[str, int]) -> None:
            self.show_levels(fqn, levels)
            self.show_temporaries(control.temporaries())
            self._say(f"{_shown(logger)} set to {_level_word(level)}")
            self.read_levels(fqn)

        self._call(control.set_level(fqn, logger, level), fqn, f"set {_shown(logger)} to {_level_word(level)}", done)

    def set_temporary(self, fqn: str, logger: str, level: int, seconds: float) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(entry: TemporaryLevel) -> None:
            self.show_levels(fqn, {logger: level})
            self.show_temporaries(control.temporaries())
            self._say(
                f"{_shown(logger)} at {_level_word(level)} for {seconds:g} s, then back to {_level_word(entry.previous)}"
            )
            self.read_levels(fqn)

        what = f"set {_shown(logger)} to {_level_word(level)} for {seconds:g} s"
        self._call(control.set_temporary(fqn, logger, level, seconds), fqn, what, done)

    def end_temporary(self, fqn: str, logger: str) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(_levels: Mapping[str, int]) -> None:
            self.show_temporaries(control.temporaries())
            self._say(f"{_shown(logger)}: temporary level ended")
            self.read_levels(fqn)

        self._call(control.end_temporary(fqn, logger), fqn, f"end the temporary level of {_shown(logger)}", done)

    def _usable_control(self) -> LoggerControl | None:
        if self.control is None:
            self._say(NO_ROS_TEXT, error=True)
        return self.control

    def _call(self, future: Future, fqn: str, what: str, then: Callable[[Any], None]) -> None:
        self.pending[fqn] = self.pending.get(fqn, 0) + 1
        self._render_heading()
        future.add_done_callback(lambda done: self.post_message(self.CallDone(done, fqn, what, then)))

    def on_logger_pane_call_done(self, message: CallDone) -> None:
        message.stop()
        fqn = message.fqn
        self.pending[fqn] = max(0, self.pending.get(fqn, 0) - 1)
        self._render_heading()
        error = message.future.exception()
        if error is None:
            message.then(message.future.result())
        else:
            self.show_failure(f"Could not {message.what}: {error}")

    def _from_control_thread(self, event: Any) -> None:
        self.post_message(self.ControlEvent(event))

    def on_logger_pane_control_event(self, message: ControlEvent) -> None:
        from ...sources.logger_control import NodesChanged, TemporaryEnded

        message.stop()
        event = message.event
        if isinstance(event, NodesChanged):
            self.show_nodes(event.nodes)
        elif isinstance(event, TemporaryEnded) and self.control is not None:
            self.show_temporaries(self.control.temporaries())
            entry = event.entry
            if event.error is not None:
                self.show_failure(
                    f"Could not put {_shown(entry.logger)} of {entry.node} back to {_level_word(entry.previous)}: {event.error}"
                )
            else:
                self._say(f"{_shown(entry.logger)} of {entry.node} is back to {_level_word(entry.previous)}")
                self.show_levels(entry.node, {entry.logger: entry.previous})
            self.read_levels(entry.node)

    # -- keys and clicks -------------------------------------------------------------------------

    def _target(self) -> tuple[str, str] | None:
        """The selected node and highlighted logger a key acts on; says why when there is none."""
        if self.control is None:
            self._say(NO_ROS_TEXT, error=True)
            return None
        node = self.node(self.selected) if self.selected else None
        if node is None:
            self._say("Select a node first", error=True)
            return None
        if not node.has_logger_services:
            self._render_loggers()
            return None
        logger = self.highlighted_logger
        if logger is None:
            logger = self._loggers_of(node).own
        if not logger and self._loggers_of(node).listing:
            self._say("Read the node's loggers first (r), or add one by name (a)", error=True)
            return None
        return node.fqn, logger

    def action_set_level(self, level: int) -> None:
        target = self._target()
        if target is not None:
            self.set_level(*target, level)

    def action_temporary(self) -> None:
        from ..screens.temporary_level import TemporaryLevelScreen

        target = self._target()
        if target is None:
            return
        fqn, logger = target

        def apply(choice: tuple[int, float] | None) -> None:
            if choice is not None:
                self.set_temporary(fqn, logger, *choice)

        self.app.push_screen(TemporaryLevelScreen(fqn, _shown(logger), DEFAULT_TEMPORARY_S), apply)

    def action_end_temporary(self) -> None:
        target = self._target()
        if target is not None:
            self.end_temporary(*target)

    def action_add_logger(self) -> None:
        self.name_input.focus()

    def action_refresh(self) -> None:
        self._note_seen_loggers(force=True)
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
        if self.selected is not None and self.control is not None and self.control.read_when_asked:
            self.read_levels(self.selected, asked=True)  # Enter opens the node: its loggers are read
        self.logger_list.focus()

    @on(OptionList.OptionSelected, "#logger-levels")
    def _logger_chosen(self, message: OptionList.OptionSelected) -> None:
        message.stop()  # Enter or a click just highlights: levels come from keys and the level bar

    @on(LevelBar.Chosen)
    def _level_clicked(self, message: LevelBar.Chosen) -> None:
        message.stop()
        if message.level < 0:
            self.action_temporary()
        else:
            self.action_set_level(message.level)

    @on(Input.Submitted, "#logger-name")
    def _name_typed(self, message: Input.Submitted) -> None:
        message.stop()
        node = self.node(self.selected) if self.selected else None
        name = message.value.strip()
        if node is None or not name:
            return
        name = self._loggers_of(node).add_typed(name)
        self.name_input.value = ""
        self._render_loggers(highlight=name)
        self.read_levels(node.fqn)
        self.logger_list.focus()

    # -- drawing ------------------------------------------------------------------------------

    def _render_all(self) -> None:
        self._render_nodes()
        self._render_loggers()

    def _render_nodes(self) -> None:
        node_list = self.node_list
        options = [Option(self._node_prompt(node), id=node.fqn) for node in self.nodes]
        with node_list.prevent(OptionList.OptionHighlighted):
            node_list.set_options(options)
            if self.selected is not None:
                node_list.highlighted = node_list.get_option_index(self.selected)
        if not self.nodes:
            self._render_heading()

    def _node_prompt(self, node: GraphNode) -> Table:
        if node.has_logger_services:
            marker = Text("")
        elif node.fqn in self.checking:
            marker = Text("checking…", style="dim italic")
        else:
            marker = Text("no logger services", style="yellow")
        return _two_columns(plain(node.fqn), marker)

    def _render_loggers(self, highlight: str | None = None) -> None:
        logger_list = self.logger_list
        if highlight is None:
            highlight = self.highlighted_logger
        now = self.clock() if self.clock is not None else 0.0
        rows = self.rows()
        node = self.node(self.selected) if self.selected else None
        own = node.logger_name if node is not None else ""
        options = [
            Option(_two_columns(plain(logger_label(row, own)), level_cell(row, now)), id=_option_id(row.name))
            for row in rows
        ]
        current = [_logger_of_option(option) for option in logger_list.options]
        if current == [row.name for row in rows]:
            for index, option in enumerate(options):
                logger_list.replace_option_prompt_at_index(index, option.prompt)
        else:
            with logger_list.prevent(OptionList.OptionHighlighted):
                logger_list.set_options(options)
        names = [row.name for row in rows]
        if highlight in names:
            logger_list.highlighted = names.index(highlight)
        elif rows and logger_list.highlighted is None:
            logger_list.highlighted = 0
        self._render_heading()
        self._render_notice()

    def _render_heading(self) -> None:
        heading = self.heading
        if self.selected is None:
            heading.update("Loggers")
            return
        busy = " …" if self.pending.get(self.selected) else ""
        heading.update(plain(f"Loggers of {self.selected}{busy}", no_wrap=True, overflow="ellipsis"))

    def _render_notice(self) -> None:
        notice = self.notice_line
        text, error = self._notice_text()
        notice.update(plain(text, lines=True))
        notice.set_class(error, "-error")

    def _notice_text(self) -> tuple[str, bool]:
        if self.control is not None and self.control.problem:
            return self.control.problem, True
        if self.notice:
            return self.notice, self.notice_is_error
        if not self.nodes:
            if self.control is None:
                return NO_ROS_TEXT, False
            return "No nodes in the ROS graph yet.", False
        node = self.node(self.selected) if self.selected else None
        if node is None:
            return "Select a node.", False
        if node.has_logger_services:
            if self.control is not None and self.control.read_when_asked and not self._loggers_of(node).levels:
                return "Enter or r: read its loggers · a: set one by name", False
            return "", False
        if node.fqn in self.checking:
            return f"Checking whether {node.fqn} offers logger services…", False
        hint = self.control.no_services_hint if self.control is not None else ENABLE_LOGGER_SERVICE_HINT
        return f"{node.fqn} has no logger services: {hint}.", False

    def _say(self, text: str, error: bool = False) -> None:
        self.notice = text
        self.notice_is_error = error
        self._render_notice()

    # -- keeping up -----------------------------------------------------------------------------

    def _loggers_of(self, node: GraphNode) -> NodeLoggers:
        loggers = self.loggers.get(node.fqn)
        if loggers is None:
            listing = self.control is not None and self.control.lists_loggers
            loggers = self.loggers[node.fqn] = NodeLoggers(node, listing=listing)
        return loggers

    def _note_seen_loggers(self, force: bool = False) -> bool:
        """Take child loggers of the selected node from the logger names seen so far."""
        seen = self.seen_loggers
        if not force and len(seen) == self._seen_count:
            return False
        self._seen_count = len(seen)
        node = self.node(self.selected) if self.selected else None
        if node is None:
            return False
        return self._loggers_of(node).note_seen(seen, {n.logger_name for n in self.nodes})

    def _checking_now(self) -> frozenset[str]:
        control = self.control
        if control is None:
            return self.checking
        return frozenset(n.fqn for n in self.nodes if not n.has_logger_services and not control.is_settled(n.fqn))

    def _refresh_checking(self) -> None:
        checking = self._checking_now()
        if checking != self.checking:
            self.checking = checking
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
        if self.control is not None:
            if self.control.problem and self.control.problem not in str(self.notice_line.content):
                self._render_notice()
            temporaries = self.control.temporaries()
            if temporaries != self.temporaries:
                self.temporaries = temporaries
                self._render_loggers()
        if self.checking:
            self._refresh_checking()
        if self._note_seen_loggers():
            self._render_loggers()
            if self.selected is not None:
                self.read_levels(self.selected)
        elif any(t.node == self.selected for t in self.temporaries):
            self._render_loggers()  # the countdown


def _option_id(logger: str) -> str:
    return "logger:" + logger


def _logger_of_option(option: Option) -> str:
    return (option.id or "logger:")[len("logger:") :]


def _shown(logger: str) -> str:
    return '"" (the default logger)' if logger == DEFAULT_LOGGER else logger


def _level_word(level: int) -> str:
    return "inherited" if level == Severity.UNSET else severity_name(level)
