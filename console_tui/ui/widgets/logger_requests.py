"""What the logger levels pane asks of a ``LoggerControl``, kept in the books of its ``LoggerPaneState``.

The pane's presenter: the pane (``logger_pane.py``) draws its state and turns keys into these
requests.
``LoggerRequests`` makes the calls, counts each as under way in the pane's state until it ends, and
when it ends (``finish``, back on the pane's thread) puts what it brought into the state, says
so, and reads the node's levels again. The control's events and the pane's tick come here too:
nodes as the graph changes, temporary levels as they run and end, child loggers seen in
records. Without a control (files only, or a test feeding the pane) nothing is called: a
request says there is no live ROS. No Textual.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping, Sequence
from concurrent.futures import Future
from dataclasses import dataclass
from typing import Any

from ...control.control_thread import LoggerControl
from ...control.events import LoggerEvent, TemporaryEnded
from ...model.loggers.logger_levels import ENABLE_LOGGER_SERVICE_HINT, GraphNode, TemporaryLevel
from ...model.loggers.logger_pane_state import NO_ROS_TEXT, LoggerPaneState, level_word, shown_logger


@dataclass(frozen=True)
class CallEnded:
    """A call's future is done: handed to ``deliver`` on the loggers thread, to ``finish`` on the pane's."""

    future: Future[Any]
    fqn: str
    #: What the call was to do, as in "Could not {what}".
    what: str
    #: Takes the call's result (on the pane's thread).
    then: Callable[[Any], None]


class LoggerRequests:
    """The logger pane's calls of ``control`` and what they bring back, kept in ``state``.

    ``deliver`` is called on the loggers thread with each ``CallEnded`` and, once ``listen``
    is called, each of the control's events: it must hand them to the thread that owns the
    state (a UI posts them to itself), there to ``finish`` the ``CallEnded`` and
    ``TemporaryEnded`` and ``set_nodes`` from the ``NodesChanged``.
    """

    def __init__(
        self,
        control: LoggerControl | None,
        deliver: Callable[[LoggerEvent | CallEnded], None],
        *,
        seen_loggers: Collection[str] = (),
    ) -> None:
        self.control = control
        self.deliver = deliver
        #: Logger names seen in records (the store's node column): where child loggers come from.
        self.seen_loggers = seen_loggers
        # Without a control nodes are ROS 2's.
        self.state = LoggerPaneState(
            has_ros=control is not None,
            no_services_hint=control.no_services_hint if control is not None else ENABLE_LOGGER_SERVICE_HINT,
            lists_loggers=control is not None and control.lists_loggers,
            read_when_asked=control.reads_when_asked if control is not None else False,
        )

    def listen(self) -> None:
        """Have the control's events delivered too."""
        if self.control is not None:
            self.control.subscribe(self.deliver)

    @property
    def problem(self) -> str:
        """The control's one-line problem, or ""."""
        return self.control.problem if self.control is not None else ""

    @property
    def looking(self) -> bool:
        """Whether the control is still discovering the graph (``LoggerControl.looking``)."""
        return self.control is not None and self.control.looking()

    # -- the graph and the selection -------------------------------------------------------------

    def set_nodes(self, nodes: Sequence[GraphNode], checking: Collection[str] | None = None) -> None:
        """The graph's nodes; ``checking`` names those whose logger services may yet appear
        (asked of the control when not given). Reads the selected node's levels when its
        logger services just appeared."""
        state = self.state
        if checking is None:
            checking = self.checking_now(nodes)
        services_appeared = state.set_nodes(nodes, checking)
        state.note_seen(self.seen_loggers, force=True)
        if services_appeared and state.selected is not None:
            self.read_levels(state.selected)

    def select(self, fqn: str, logger: str | None = None) -> bool | None:
        """Select node ``fqn`` (offering ``logger``), reading its levels when the selection
        changed or a logger was named. None when there is no such node; else whether the
        selection changed."""
        changed = self.state.select(fqn, logger)
        if changed is None:
            return None
        self.state.note_seen(self.seen_loggers, force=True)
        if changed or logger is not None:
            self.read_levels(fqn)
        return changed

    def opened(self) -> bool:
        """The pane opens: take the child loggers seen so far. True when the "checking" marks changed."""
        self.state.note_seen(self.seen_loggers)
        return self.refresh_checking()

    def checking_now(self, nodes: Sequence[GraphNode] | None = None) -> frozenset[str]:
        """The nodes (of ``nodes``, else the state's) whose logger services may yet appear."""
        control = self.control
        if control is None:
            return self.state.checking
        return self.state.unsettled(control.is_settled, self.state.nodes if nodes is None else nodes)

    def refresh_checking(self) -> bool:
        """The "checking" marks as the control sees them now; True when they changed."""
        checking = self.checking_now()
        if checking == self.state.checking:
            return False
        self.state.checking = checking
        return True

    def add_logger(self, typed: str) -> str | None:
        """A logger name typed for the selected node: offered and its level read; the name as kept."""
        name = self.state.add_logger(typed)
        if name is not None and self.state.selected is not None:
            self.read_levels(self.state.selected)
        return name

    def reread(self) -> None:
        """``r``: child loggers seen again, and the selected node's levels read (asked for)."""
        self.state.note_seen(self.seen_loggers, force=True)
        if self.state.selected is not None:
            self.read_levels(self.state.selected, asked=True)

    # -- keeping up (the pane's tick) ----------------------------------------------------------------

    def take_temporaries(self) -> bool:
        """The control's running temporary levels into the state; True when they changed."""
        if self.control is None:
            return False
        temporaries = self.control.temporaries()
        if temporaries == self.state.temporaries:
            return False
        self.state.temporaries = temporaries
        return True

    def new_child_loggers(self) -> bool:
        """Child loggers of the selected node newly seen in records; True when there are
        some (the node's levels are then read)."""
        if not self.state.note_seen(self.seen_loggers):
            return False
        if self.state.selected is not None:
            self.read_levels(self.state.selected)
        return True

    # -- calls ---------------------------------------------------------------------------------

    def read_levels(self, fqn: str, *, asked: bool = False) -> None:
        """Read ``fqn``'s levels; where they are read only when asked (ROS 1), only when ``asked``."""
        names = self.state.names_to_read(fqn)
        if self.control is None or names is None or (self.state.reads_when_asked(fqn) and not asked):
            return

        def read(levels: Mapping[str, int]) -> None:
            self.state.set_levels(fqn, levels)

        self._call(self.control.get_levels(fqn, names), fqn, "read the levels", read)

    def set_level(self, fqn: str, logger: str, level: int) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(levels: Mapping[str, int]) -> None:
            self.state.level_set(fqn, logger, level, levels)
            self._levels_changed(control, fqn)

        what = f"set {shown_logger(logger)} to {level_word(level)}"
        self._call(control.set_level(fqn, logger, level), fqn, what, done)

    def set_temporary(self, fqn: str, logger: str, level: int, seconds: float) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(entry: TemporaryLevel) -> None:
            self.state.temporary_set(fqn, entry, seconds)
            self._levels_changed(control, fqn)

        what = f"set {shown_logger(logger)} to {level_word(level)} for {seconds:g} s"
        self._call(control.set_temporary(fqn, logger, level, seconds), fqn, what, done)

    def end_temporary(self, fqn: str, logger: str) -> None:
        control = self._usable_control()
        if control is None:
            return

        def done(_levels: Mapping[str, int]) -> None:
            self.state.say(f"{shown_logger(logger)}: temporary level ended")
            self._levels_changed(control, fqn)

        self._call(control.end_temporary(fqn, logger), fqn, f"end the temporary level of {shown_logger(logger)}", done)

    def finish(self, ended: CallEnded | TemporaryEnded) -> str | None:
        """A call ended, or the control put a temporary level back (on the pane's thread): what
        it brought into the state. Returns the failure to report, if it failed."""
        if isinstance(ended, TemporaryEnded):
            if self.control is None:
                return None
            failure = self.state.temporary_ended(ended.entry, ended.error)
            self._levels_changed(self.control, ended.entry.node)
            return failure
        self.state.call_ended(ended.fqn)
        error = ended.future.exception()
        if error is not None:
            return f"Could not {ended.what}: {error}"
        ended.then(ended.future.result())
        return None

    def _levels_changed(self, control: LoggerControl, fqn: str) -> None:
        self.state.temporaries = control.temporaries()
        self.read_levels(fqn)

    def _usable_control(self) -> LoggerControl | None:
        if self.control is None:
            self.state.say(NO_ROS_TEXT, error=True)
        return self.control

    def _call(self, future: Future[Any], fqn: str, what: str, then: Callable[[Any], None]) -> None:
        self.state.call_started(fqn)
        future.add_done_callback(lambda done: self.deliver(CallEnded(done, fqn, what, then)))
