"""What the logger levels pane shows, without the screen: the graph's nodes, the selected node,
its loggers and their levels, the calls under way per node, and the one-line notice.

``LoggerPaneState`` is to the logger levels pane what ``LogView`` is to the table: the pane draws
it and turns keys into calls (``ui/widgets/logger_requests.py`` makes them and brings their
outcomes here); the state keeps the books (which node is selected, what was read, which
calls are pending, what to say when a call ends). No ROS, no Textual.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Mapping, Sequence

from ..levels import Severity, severity_name
from .logger_levels import DEFAULT_LOGGER, GraphNode, LoggerRow, NodeLoggers, TemporaryLevel, node_of_logger

#: What the pane says when this run has no live ROS (files only).
NO_ROS_TEXT = "No live ROS in this console (files only): logger levels cannot be read or set."
#: While the graph is still being discovered and no node has been found.
LOOKING_TEXT = "Looking for the ROS graph's nodes…"


def shown_logger(logger: str) -> str:
    """A logger's name in a sentence: the default logger is named, not an empty string."""
    return '"" (the default logger)' if logger == DEFAULT_LOGGER else logger


def level_word(level: int) -> str:
    return "inherited" if level == Severity.UNSET else severity_name(level)


class LoggerPaneState:
    """The nodes, the selected node's loggers and levels, calls under way, and the notice."""

    def __init__(
        self,
        *,
        has_ros: bool = True,
        no_services_hint: str = "",
        lists_loggers: bool = False,
        read_when_asked: bool | Callable[[str], bool] = False,
    ) -> None:
        #: False when there is no logger control: nothing can be read or set.
        self.has_ros = has_ros
        #: How a node gets the logger services (said of a node without them).
        self.no_services_hint = no_services_hint
        #: A read lists every logger of the node (ROS 1): the loggers offered are those.
        self.lists_loggers = lists_loggers
        self._read_when_asked = read_when_asked
        self.nodes: tuple[GraphNode, ...] = ()
        #: Nodes whose logger services may yet appear (seen too recently to tell).
        self.checking: frozenset[str] = frozenset()
        self.selected: str | None = None
        self.temporaries: tuple[TemporaryLevel, ...] = ()
        #: Calls under way, per node.
        self.pending: dict[str, int] = {}
        self.notice = ""
        self.notice_is_error = False
        self._loggers: dict[str, NodeLoggers] = {}
        self._seen_count = -1

    # -- the graph and the selection -------------------------------------------------------------

    def node(self, fqn: str | None) -> GraphNode | None:
        return None if fqn is None else next((node for node in self.nodes if node.fqn == fqn), None)

    @property
    def selected_node(self) -> GraphNode | None:
        return self.node(self.selected)

    def set_nodes(self, nodes: Sequence[GraphNode], checking: Collection[str]) -> bool:
        """The graph's nodes now. True when the selected node's logger services just appeared
        (its levels are to be read)."""
        before = {node.fqn: node for node in self.nodes}
        self.nodes = tuple(nodes)
        self.checking = frozenset(checking)
        if self.selected is not None and self.node(self.selected) is None:
            self.say(f"{self.selected} left the ROS graph")
            self.selected = None
            return False
        node = self.selected_node
        old = before.get(self.selected or "")
        return node is not None and node.has_logger_services and not (old and old.has_logger_services)

    def select(self, fqn: str, logger: str | None = None) -> bool | None:
        """Select node ``fqn`` (offering ``logger`` among its loggers). None when there is no such
        node; else whether the selection changed."""
        node = self.node(fqn)
        if node is None:
            return None
        changed = fqn != self.selected
        self.selected = fqn
        loggers = self.loggers_of(node)
        if logger is not None and logger not in loggers.names():
            loggers.add_typed(logger)
        if changed:
            self.notice = ""
        return changed

    def node_logging_as(self, logger: str, robot: str = "") -> GraphNode | None:
        """The node whose messages carry this logger name (on ``robot``, in a fleet); None after
        saying there is none."""
        node = node_of_logger(logger, self.nodes, robot)
        if node is None:
            where = f" of {robot}" if robot else ""
            self.say(f"No node in the ROS graph{where} logs as {logger!r} (it may have exited)", error=True)
        return node

    def loggers_of(self, node: GraphNode) -> NodeLoggers:
        loggers = self._loggers.get(node.fqn)
        if loggers is None:
            loggers = self._loggers[node.fqn] = NodeLoggers(node, listing=self.lists_loggers)
        return loggers

    def rows(self) -> list[LoggerRow]:
        """The selected node's logger rows, as shown."""
        node = self.selected_node
        if node is None or not node.has_logger_services:
            return []
        return self.loggers_of(node).rows(self.temporaries)

    def note_seen(self, seen: Collection[str], *, force: bool = False) -> bool:
        """Take child loggers of the selected node from the logger names seen in records;
        True when one is new."""
        if not force and len(seen) == self._seen_count:
            return False
        self._seen_count = len(seen)
        node = self.selected_node
        if node is None:
            return False
        return self.loggers_of(node).note_seen(seen, {n.logger_name for n in self.nodes})

    @staticmethod
    def unsettled(is_settled: Callable[[str], bool], nodes: Iterable[GraphNode]) -> frozenset[str]:
        """The nodes without logger services that ``is_settled`` cannot vouch for yet."""
        return frozenset(n.fqn for n in nodes if not n.has_logger_services and not is_settled(n.fqn))

    def names_to_read(self, fqn: str) -> list[str] | None:
        """What a level read of ``fqn`` asks for; None when it cannot be read."""
        node = self.node(fqn)
        if node is None or not node.has_logger_services:
            return None
        return self.loggers_of(node).names_to_read()

    def target(self, highlighted: str | None) -> tuple[str, str] | None:
        """The selected node and the logger a key acts on (the highlighted one, else the
        node's own); None after saying why there is none."""
        if not self.has_ros:
            self.say(NO_ROS_TEXT, error=True)
            return None
        node = self.selected_node
        if node is None:
            self.say("Select a node first", error=True)
            return None
        if not node.has_logger_services:
            return None
        loggers = self.loggers_of(node)
        logger = highlighted if highlighted is not None else loggers.own
        if not logger and loggers.listing:
            self.say("Read the node's loggers first (r), or add one by name (a)", error=True)
            return None
        return node.fqn, logger

    def add_logger(self, name: str) -> str | None:
        """Offer a typed logger name on the selected node; returns the name as kept."""
        node = self.selected_node
        if node is None or not name.strip():
            return None
        return self.loggers_of(node).add_typed(name)

    # -- calls and what they bring back ------------------------------------------------------------

    def call_started(self, fqn: str) -> None:
        self.pending[fqn] = self.pending.get(fqn, 0) + 1

    def call_ended(self, fqn: str) -> None:
        self.pending[fqn] = max(0, self.pending.get(fqn, 0) - 1)

    def set_levels(self, fqn: str, levels: Mapping[str, int]) -> bool:
        """Levels read from (or just set on) node ``fqn``; True when it is the selected one."""
        node = self.node(fqn)
        if node is None:
            return False
        self.loggers_of(node).update_levels(levels)
        return fqn == self.selected

    def level_set(self, fqn: str, logger: str, level: int, levels: Mapping[str, int]) -> None:
        self.set_levels(fqn, levels)
        self.say(f"{shown_logger(logger)} set to {level_word(level)}")

    def temporary_set(self, fqn: str, entry: TemporaryLevel, seconds: float) -> None:
        self.set_levels(fqn, {entry.logger: entry.level})
        self.say(
            f"{shown_logger(entry.logger)} at {level_word(entry.level)} for {seconds:g} s, "
            f"then back to {level_word(entry.previous)}"
        )

    def temporary_ended(self, entry: TemporaryLevel, error: object | None) -> str | None:
        """A temporary level is over; returns the failure to report, if it could not be put back."""
        what = f"{shown_logger(entry.logger)} of {entry.node}"
        if error is not None:
            return f"Could not put {what} back to {level_word(entry.previous)}: {error}"
        self.set_levels(entry.node, {entry.logger: entry.previous})
        self.say(f"{what} is back to {level_word(entry.previous)}")
        return None

    # -- what the pane says ---------------------------------------------------------------------------

    def say(self, text: str, error: bool = False) -> None:
        self.notice = text
        self.notice_is_error = error

    def heading(self) -> str:
        if self.selected is None:
            return "Loggers"
        busy = " …" if self.pending.get(self.selected) else ""
        return f"Loggers of {self.selected}{busy}"

    def notice_text(self, problem: str = "", read_hint: str = "", *, looking: bool = False) -> tuple[str, bool]:
        """The notice line and whether it is an error: the control's ``problem`` first, then
        what was last said, then what the selection calls for (``read_hint`` says how to read
        a node's loggers where they are read only when asked; ``looking``: the graph is still
        being discovered)."""
        if problem:
            return problem, True
        if self.notice:
            return self.notice, self.notice_is_error
        if not self.nodes:
            if not self.has_ros:
                return NO_ROS_TEXT, False
            return (LOOKING_TEXT if looking else "No nodes in the ROS graph yet."), False
        node = self.selected_node
        if node is None:
            return "Select a node.", False
        if node.has_logger_services:
            if self.reads_when_asked(node.fqn) and not self.loggers_of(node).levels:
                return read_hint, False
            return "", False
        if node.fqn in self.checking:
            return f"Checking whether {node.fqn} offers logger services…", False
        hint = f": {self.no_services_hint}" if self.no_services_hint else ""
        return f"{node.fqn} has no logger services{hint}.", False

    def reads_when_asked(self, fqn: str) -> bool:
        """Whether ``fqn``'s levels are read only when the user asks (ROS 1's nodes, also in
        a fleet with ROS 2 robots), never on highlighting it."""
        asked = self._read_when_asked
        return asked(fqn) if callable(asked) else asked

    def counting_down(self) -> bool:
        """Whether a temporary level of the selected node is running (its countdown moves)."""
        return any(t.node == self.selected for t in self.temporaries)
