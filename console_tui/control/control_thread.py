"""Logger levels of a ROS graph's nodes, whatever the ROS: the control, the common part.

A ``LoggerControl`` runs one background thread (``console-tui-loggers``) that makes every ROS
call. Its methods may be called from any thread and never block: calls return
``concurrent.futures.Future`` objects that always complete, within the call timeout, with a
result or a ``LoggerCallError`` whose text is the message to show. The futures' done callbacks
run on the loggers thread: a UI posts the outcome back to its own thread from there; a command
line waits with ``future.result()``. Levels are numbers on the ROS 2 scale everywhere
(``model.levels.Severity``, 0 = unset). Temporary levels are restored by the loggers thread when
their time is up, and by ``close`` (a process killed outright leaves them set).

Beside it: ``errors.py``, ``events.py``, ``graph.py``, ``calls.py``. A ROS gets its control by
subclassing ``LoggerControl`` (what a subclass provides: the class's docstring).
"""

from __future__ import annotations

import functools
import threading
import time
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import Future
from typing import Any

from ..model.loggers.logger_levels import GraphNode, TemporaryLevel, TemporaryLevels
from ..system.thread_names import os_named
from .calls import Call
from .errors import (
    CallTimedOut,
    ControlClosed,
    LevelRefused,
    NodeGone,
    NoLoggerServices,
    call_error,
    unsendable,
)
from .events import LoggerEvent, NodesChanged, TemporaryEnded
from .futures import done_future, failed_future, settle, then
from .graph import GRAPH_MIN_S, GRAPH_PERIOD_S, GRAPH_QUIET_S, GraphSnapshot, GraphWait, GraphWatch

CALL_TIMEOUT_S = 2.0
#: Discovery is busiest just after start: look at the graph more often then.
STARTUP_GRAPH_PERIOD_S = 0.1
STARTUP_S = 3.0
RESTORE_ATTEMPTS = 3
RESTORE_RETRY_S = 1.0
MAX_IDLE_S = 0.1


class LoggerControl(ABC):
    """Lists the graph's nodes and gets and sets their logger levels, off the caller's thread.

    ``start`` it, ``subscribe`` to its events, call it from anywhere, ``close`` it at exit.
    Nodes are named by their fully qualified name (``GraphNode.fqn``) in every call. ``close``
    restores the temporary levels still running before it returns (each restore waits up to
    the call timeout).

    A subclass (each ROS's ``logger_control.py``) provides, called on the loggers thread unless
    said otherwise:

    - ``_open()``: set up (a node, a connection to the master). An error ends the control and
      becomes its ``problem``.
    - ``_look()``: the graph now, as ``(nodes, with_services)``: every node as a ``GraphNode``
      whose ``has_logger_services`` says whether it offers the logger services, and the fully
      qualified names of the nodes that show any service at all. Console-tui's own nodes and hidden
      ones are left out here, not there.
    - ``_call_get(node, names)`` and ``_call_set(node, levels, restore=...)`` (any thread): a future
      of ``{logger: level}``. Build a request, pass it to ``self._submit(...)``, map its reply with
      ``futures.then``; raise ``LevelRefused`` for levels the node refused or the ROS cannot express.
    - ``_send(call)``: start a submitted call, returning an object with ``done()``, ``exception()``
      and ``result()`` (any future), or None while the service cannot take it yet (asked again on
      the next pass). Never blocks: a ROS whose calls block runs them on a worker thread.
    - ``_drop(call)``: forget a sent call given up on (timed out, node gone, closing).
    - ``_shutdown()``: release everything; called once at the end, even after a failed ``_open``.

    and may set ``lists_loggers``, ``read_when_asked``, ``graph_min_s`` and ``graph_quiet_s`` (see
    them), and may override ``_lost(call)`` (a sent call's service went away: default never),
    ``_wait(timeout)`` and ``_wake()`` (sleep until woken from any thread: default an Event), and
    ``no_services_hint`` (how a user gives a node the logger services).
    """

    #: Appended to ``NoLoggerServices``: how a user gives a node the logger services.
    no_services_hint = ""
    #: How long the graph must be watched, and then stay unchanged, to be taken as complete
    #: (``wait_for_graph``); a ROS whose graph comes whole from one place (a ROS 1 master) may
    #: make them shorter.
    #: Looking at the graph asks a peer over the network (a ROS 1 master), rather than
    #: reading what this process already knows (ROS 2's discovery): ``watch_graph``.
    remote_graph = False
    graph_min_s = GRAPH_MIN_S
    graph_quiet_s = GRAPH_QUIET_S
    #: A read answers with every logger the node has, not only the names asked for (ROS 1).
    lists_loggers = False
    #: Read a node's levels only when the user asks, never because a node is highlighted
    #: (ROS 1: ``get_loggers`` can crash roscpp nodes, so nothing sweeps it).
    read_when_asked = False

    def __init__(
        self,
        *,
        call_timeout: float = CALL_TIMEOUT_S,
        include_hidden: bool = False,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.call_timeout = call_timeout
        self.clock = clock
        self._lock = threading.Lock()
        self._graph = GraphWatch(
            clock, include_hidden=include_hidden, halted=lambda: self._stop.is_set(), problem=lambda: self.problem
        )
        self._temporaries = TemporaryLevels(clock)
        self._submitted: list[Call] = []
        self._listeners: list[Callable[[LoggerEvent], None]] = []
        self._stop = threading.Event()
        self._woken = threading.Event()
        self._watched = threading.Event()
        self._watched.set()
        #: Turns of the loggers thread so far (for tests: time passing without a clock).
        self.passes = 0
        self._closed = False
        self._thread: threading.Thread | None = None
        #: When ``start()`` was called (on ``clock``), or None before.
        self._started_at: float | None = None
        #: A one-line problem for the status bar, or "".
        self.problem = ""

    # -- control -----------------------------------------------------------------------------

    def reads_when_asked(self, fqn: str) -> bool:
        """Whether ``fqn``'s levels are read only when the user asks (``read_when_asked``)."""
        return self.read_when_asked

    def start(self) -> None:
        """Start the loggers thread (once: later calls do nothing)."""
        with self._lock:
            if self._thread is not None or self._stop.is_set():
                return
            self._started_at = self.clock()
            self._thread = threading.Thread(target=os_named(self._run), name="console-tui-loggers", daemon=True)
        self._thread.start()

    def looking(self) -> bool:
        """Whether the graph is still being discovered: from ``start()`` until it has been
        watched for ``graph_min_s`` and no node came or went for ``graph_quiet_s``."""
        started = self._started_at
        if started is None or self._stop.is_set():
            return False
        graph = self._graph.snapshot
        return not graph.refreshes or self.clock() < graph.quiet_until(started, self.graph_min_s, self.graph_quiet_s)

    def close(self, timeout: float | None = None) -> None:
        """Restore running temporary levels, fail calls still waiting, stop the thread."""
        self._stop.set()
        self._trigger()
        if self._thread is not None:
            self._thread.join(self.call_timeout + 2.0 if timeout is None else timeout)

    def subscribe(self, listener: Callable[[LoggerEvent], None]) -> None:
        """Call ``listener(event)`` on the loggers thread for every ``LoggerEvent``.

        It must be quick and must not block (post the event to the UI and return).
        """
        with self._lock:
            self._listeners.append(listener)

    def no_services(self, node: str) -> NoLoggerServices:
        """The error saying that ``node`` has no logger services, with this ROS's hint."""
        return NoLoggerServices(node, self.no_services_hint)

    # -- the graph -----------------------------------------------------------------------------

    @property
    def graph_watched(self) -> bool:
        return self._watched.is_set()

    def watch_graph(self, watched: bool) -> None:
        """Look at the graph every ``GRAPH_PERIOD_S`` only while ``watched`` (the default),
        when looking asks a peer over the network (``remote_graph``): the UI watches only
        while its logger pane is open. A call to an unknown node still looks once."""
        if watched and not self._watched.is_set():
            self._watched.set()
            self._trigger()
        elif not watched and self.remote_graph:
            self._watched.clear()

    @property
    def nodes(self) -> tuple[GraphNode, ...]:
        """The graph's nodes as last seen, sorted by name (console-tui's own never included)."""
        return self._graph.snapshot.nodes

    def node(self, fqn: str) -> GraphNode | None:
        return self._graph.snapshot.by_fqn.get(fqn)

    def is_settled(self, fqn: str) -> bool:
        """Whether ``has_logger_services`` of that node can be believed yet.

        Services are discovered a little after their node: show an unsettled node without
        them as "checking", not as "no logger services".
        """
        graph = self._graph.snapshot
        node = graph.by_fqn.get(fqn)
        return node is not None and graph.settled(node, self.clock())

    def find_node(self, query: str, wait: float) -> list[GraphNode]:
        """Blocking: the nodes ``query`` names, waiting up to ``wait`` s (``GraphWatch.find_node``)."""
        return self._graph.find_node(query, wait)

    def wait_for_graph(self, deadline: float) -> GraphWait:
        """Blocking: the nodes once the graph has settled (watched for ``graph_min_s``, then
        unchanged for ``graph_quiet_s``), or at the latest after ``deadline`` s."""
        return self._graph.wait_for_graph(deadline, self.graph_min_s, self.graph_quiet_s)

    # -- calls ---------------------------------------------------------------------------------

    def get_levels(self, node: str, names: Iterable[str]) -> Future[dict[str, int]]:
        """The levels of ``names`` on ``node``: 0 for a logger with no level of its own."""
        return self._call_get(node, list(names))

    def set_levels(self, node: str, levels: Mapping[str, int]) -> Future[dict[str, int]]:
        """Set levels (0 unsets a logger); the result is ``levels``. Ends their temporary levels."""

        def done(result: dict[str, int]) -> dict[str, int]:
            with self._lock:
                for name in result:
                    self._temporaries.cancel(node, name)
            return result

        return then(self._set(node, levels), done)

    def set_level(self, node: str, logger: str, level: int) -> Future[dict[str, int]]:
        return self.set_levels(node, {logger: level})

    def set_temporary(self, node: str, logger: str, level: int, seconds: float) -> Future[TemporaryLevel]:
        """Set ``level`` now and put the level it replaces back after ``seconds``.

        Setting a temporary level again before the first one ends keeps the original level
        to come back to. The result is the running ``TemporaryLevel``.
        """
        with self._lock:
            running = self._temporaries.get(node, logger)
        if running is not None:
            previous: Future[int] = done_future(running.previous)
        else:
            previous = then(self.get_levels(node, [logger]), lambda levels: levels.get(logger, 0))

        def register(before: int) -> TemporaryLevel:
            with self._lock:
                return self._temporaries.start(node, logger, level, before, seconds)

        return then(previous, lambda before: then(self._set(node, {logger: level}), lambda _: register(before)))

    def end_temporary(self, node: str, logger: str) -> Future[dict[str, int]]:
        """End a temporary level now, putting its previous level back (done at once if none runs)."""
        with self._lock:
            entry = self._temporaries.cancel(node, logger)
        if entry is None:
            return done_future({})
        return self._restore(entry)

    def temporaries(self) -> tuple[TemporaryLevel, ...]:
        """The temporary levels running, soonest first. ``entry.remaining(control.clock())``."""
        with self._lock:
            return self._temporaries.pending()

    # -- what a ROS provides ---------------------------------------------------------------------

    @abstractmethod
    def _open(self) -> None: ...

    @abstractmethod
    def _look(self) -> tuple[Iterable[GraphNode], frozenset[str]]: ...

    @abstractmethod
    def _call_get(self, node: str, names: list[str]) -> Future[dict[str, int]]: ...

    @abstractmethod
    def _call_set(self, node: str, levels: dict[str, int], *, restore: bool) -> Future[dict[str, int]]: ...

    @abstractmethod
    def _send(self, call: Call) -> Any: ...

    @abstractmethod
    def _drop(self, call: Call) -> None: ...

    @abstractmethod
    def _shutdown(self) -> None: ...

    def _lost(self, call: Call) -> bool:
        return False

    def _wait(self, timeout: float) -> None:
        self._woken.wait(timeout)
        self._woken.clear()

    def _wake(self) -> None:
        self._woken.set()

    # -- internals: any thread ----------------------------------------------------------------

    def _submit(self, node: str, service: str, request: Any, restore: bool = False) -> Future[Any]:
        """Queue a call for the loggers thread: a future of the node's raw reply."""
        future: Future[Any] = Future()
        call = Call(node, service, request, self.clock() + self.call_timeout, future, restore)
        with self._lock:
            if self._closed:
                future.set_exception(ControlClosed(node))
                return future
            self._submitted.append(call)
        self._trigger()
        return future

    def _set(self, node: str, levels: Mapping[str, int], *, restore: bool = False) -> Future[dict[str, int]]:
        levels = dict(levels)
        bad = unsendable(levels)
        if bad:
            return failed_future(LevelRefused(node, bad))
        return self._call_set(node, levels, restore=restore)

    def _trigger(self) -> None:
        try:
            self._wake()
        except Exception:
            pass

    def _restore(self, entry: TemporaryLevel) -> Future[dict[str, int]]:
        return self._set(entry.node, {entry.logger: entry.previous}, restore=True)

    # -- internals: the loggers thread -------------------------------------------------------

    def _run(self) -> None:
        calls: list[Call] = []
        next_graph = started = self.clock()
        try:
            self._open()
            while True:
                now = self.clock()
                self.passes += 1
                if now >= next_graph and self._watched.is_set():
                    next_graph = now + (STARTUP_GRAPH_PERIOD_S if now - started < STARTUP_S else GRAPH_PERIOD_S)
                    self._refresh_graph(now)
                with self._lock:
                    new, self._submitted = self._submitted, []
                if any(call.node not in self._graph.snapshot.by_fqn for call in new):
                    self._refresh_graph(now)
                calls.extend(new)
                if self._stop.is_set() and not self._closed:
                    calls = self._begin_closing(calls)
                graph = self._graph.snapshot
                calls = [call for call in calls if not self._advance(call, now, graph)]
                if self._stop.is_set():
                    if not calls and not self._submitted:
                        break
                else:
                    self._restore_due()
                self._wait(self._idle_time(calls, next_graph if self._watched.is_set() else now + MAX_IDLE_S))
        except Exception as error:  # the ROS went down under us, or a bug: say so, never hang
            if not self._stop.is_set():
                self.problem = f"logger levels stopped: {type(error).__name__}: {error}"
        finally:
            with self._lock:
                self._closed = True
                leftover, self._submitted = calls + self._submitted, []
            for call in leftover:
                settle(call.future, error=ControlClosed(call.node))
            try:
                self._shutdown()
            except Exception:
                pass

    def _idle_time(self, calls: list[Call], next_graph: float) -> float:
        with self._lock:
            due = self._temporaries.next_deadline()
        wake = min([next_graph, *(call.deadline for call in calls), *([due] if due is not None else [])])
        return max(0.0, min(MAX_IDLE_S, wake - self.clock()))

    def _refresh_graph(self, now: float) -> None:
        looked, with_services = self._look()
        if self._graph.update(looked, with_services, now):
            self._emit(NodesChanged(self._graph.snapshot.nodes))

    def _advance(self, call: Call, now: float, graph: GraphSnapshot) -> bool:
        return call.advance(
            now,
            graph,
            send=self._send,
            drop=self._drop,
            lost=self._lost,
            no_services=self.no_services,
            timeout=self.call_timeout,
        )

    def _restore_due(self) -> None:
        with self._lock:
            due = self._temporaries.take_due()
        for entry in due:
            self._restore(entry).add_done_callback(functools.partial(self._restored, entry))

    def _restored(self, entry: TemporaryLevel, future: Future[Any]) -> None:
        error = future.exception()
        if (
            isinstance(error, (CallTimedOut, NodeGone))
            and entry.attempts + 1 < RESTORE_ATTEMPTS
            and not self._closed
            and self.node(entry.node) is not None
        ):
            with self._lock:
                self._temporaries.retry_later(entry, RESTORE_RETRY_S)
            return
        self._emit(TemporaryEnded(entry, call_error(entry.node, error)))

    def _restored_closing(self, entry: TemporaryLevel, future: Future[Any]) -> None:
        self._emit(TemporaryEnded(entry, call_error(entry.node, future.exception())))

    def _begin_closing(self, calls: list[Call]) -> list[Call]:
        """Fail the calls under way, and put every temporary level back; returns the calls left."""
        with self._lock:
            entries = self._temporaries.take_all()
        for call in calls:
            if not call.restore:
                if call.sent is not None:
                    self._drop(call)
                settle(call.future, error=ControlClosed(call.node))
        for entry in entries:
            self._restore(entry).add_done_callback(functools.partial(self._restored_closing, entry))
        with self._lock:
            self._closed = True
        return [call for call in calls if call.restore]

    def _emit(self, event: LoggerEvent) -> None:
        with self._lock:
            listeners = list(self._listeners)
        for listener in listeners:
            try:
                listener(event)
            except Exception:
                pass
