"""Logger levels of the graph's nodes, through their ``get_logger_levels`` / ``set_logger_levels``.

``LoggerControl`` runs one background thread that owns a hidden node, its service clients
and an executor: every ROS call happens there. Its methods may be called from any thread
and never block: calls return ``concurrent.futures.Future`` objects that always complete,
within the call timeout, with a result or a ``LoggerCallError`` whose text is the message
to show. A UI adds a done callback that posts the outcome back to its own thread (the
callback runs on the loggers thread); a command line waits with ``future.result()``.

Temporary levels are restored by the same thread when their time is up, whatever the UI
does. ``close`` restores the ones still running before it returns (each restore waits up
to the call timeout); a process killed outright leaves them set.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import Future
from dataclasses import dataclass, field
from typing import Any, TypeVar

from ...model.levels import Severity
from ...model.logger_levels import (
    DEFAULT_LOGGER,
    ENABLE_LOGGER_SERVICE_HINT,
    OWN_NODE_PREFIX,
    GraphNode,
    TemporaryLevel,
    TemporaryLevels,
    match_nodes,
)
from .runtime import RosRuntime

CALL_TIMEOUT_S = 2.0
GRAPH_PERIOD_S = 0.5
#: Discovery is busiest just after start: look at the graph more often then.
STARTUP_GRAPH_PERIOD_S = 0.1
STARTUP_S = 3.0
#: Services are discovered a little after their node: a node is taken to have no logger
#: services once it has been seen this long and shows other services (parameters), or
#: three times as long when it shows none at all.
NO_SERVICES_GRACE_S = 1.5
RESTORE_ATTEMPTS = 3
RESTORE_RETRY_S = 1.0
MAX_IDLE_S = 0.1

GET_SERVICE = "get_logger_levels"
SET_SERVICE = "set_logger_levels"
_SERVICE_TYPES = {GET_SERVICE: "rcl_interfaces/srv/GetLoggerLevels", SET_SERVICE: "rcl_interfaces/srv/SetLoggerLevels"}

T = TypeVar("T")


# -- failures and events --------------------------------------------------------------------


class LoggerCallError(Exception):
    """A logger-level call that failed; ``str()`` is the message to show."""

    def __init__(self, node: str, message: str) -> None:
        super().__init__(message)
        self.node = node


class NodeNotFound(LoggerCallError):
    """No node of that name is in the graph."""

    def __init__(self, node: str) -> None:
        super().__init__(node, f"{node}: no such node in the ROS graph")


class NoLoggerServices(LoggerCallError):
    """The node is there but offers no logger services (Humble, or not enabled)."""

    def __init__(self, node: str) -> None:
        super().__init__(node, f"{node} has no logger services: {ENABLE_LOGGER_SERVICE_HINT}")


class CallTimedOut(LoggerCallError):
    def __init__(self, node: str, seconds: float) -> None:
        super().__init__(node, f"{node} did not answer within {seconds:g} s (busy, or gone)")


class NodeGone(LoggerCallError):
    def __init__(self, node: str) -> None:
        super().__init__(node, f"{node} went away during the call")


class LevelRefused(LoggerCallError):
    """The node refused some levels; ``refused`` maps each logger name to the node's reason."""

    def __init__(self, node: str, refused: Mapping[str, str]) -> None:
        self.refused = dict(refused)
        details = "; ".join(
            f"{name or '(default)'}: {reason or 'no reason given'}" for name, reason in self.refused.items()
        )
        super().__init__(node, f"{node} refused the level: {details}")


class ControlClosed(LoggerCallError):
    def __init__(self, node: str) -> None:
        super().__init__(node, "logger control is closed")


@dataclass(frozen=True)
class NodesChanged:
    """The graph's nodes changed (or their logger services appeared)."""

    nodes: tuple[GraphNode, ...]


@dataclass(frozen=True)
class TemporaryEnded:
    """A temporary level is over: ``previous`` restored, or ``error`` says why not."""

    entry: TemporaryLevel
    error: LoggerCallError | None = None


LoggerEvent = NodesChanged | TemporaryEnded


# -- the control --------------------------------------------------------------------------


@dataclass
class _Call:
    node: str
    service: str
    request: Any
    deadline: float
    future: Future
    #: Puts a temporary level back: still sent while closing.
    restore: bool = False
    client: Any = None
    sent: Any = None


@dataclass
class _Graph:
    nodes: tuple[GraphNode, ...] = ()
    by_fqn: dict[str, GraphNode] = field(default_factory=dict)
    first_seen: dict[str, float] = field(default_factory=dict)
    #: Nodes that show at least one service of any kind.
    with_services: frozenset[str] = frozenset()
    refreshes: int = 0

    def settled(self, node: GraphNode, now: float) -> bool:
        """Whether what the graph says of the node's logger services can be believed."""
        if node.has_logger_services:
            return True
        seen_for = now - self.first_seen.get(node.fqn, now)
        grace = NO_SERVICES_GRACE_S if node.fqn in self.with_services else 3 * NO_SERVICES_GRACE_S
        return seen_for >= grace


class LoggerControl:
    """Lists the graph's nodes and gets and sets their logger levels, off the caller's thread.

    ``start`` it, ``subscribe`` to its events, call it from anywhere, ``close`` it at exit.
    Nodes are named by their fully qualified name (``GraphNode.fqn``) in every call.
    """

    def __init__(
        self,
        runtime: RosRuntime,
        *,
        call_timeout: float = CALL_TIMEOUT_S,
        include_hidden: bool = False,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.runtime = runtime
        self.call_timeout = call_timeout
        self.include_hidden = include_hidden
        self.clock = clock
        self._lock = threading.Lock()
        self._graph_changed = threading.Condition(self._lock)
        self._graph = _Graph()
        self._temporaries = TemporaryLevels(clock)
        self._submitted: list[_Call] = []
        self._listeners: list[Callable[[LoggerEvent], None]] = []
        self._stop = threading.Event()
        self._closed = False
        self._wake: Any = None
        self._thread: threading.Thread | None = None
        #: A one-line problem for the status bar, or "".
        self.problem = ""

    # -- control -----------------------------------------------------------------------------

    def start(self) -> None:
        self._thread = threading.Thread(target=self._run, name="console-tui-loggers", daemon=True)
        self._thread.start()

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

    # -- the graph -----------------------------------------------------------------------------

    @property
    def nodes(self) -> tuple[GraphNode, ...]:
        """The graph's nodes as last seen, sorted by name (console-tui's own never included)."""
        return self._graph.nodes

    def node(self, fqn: str) -> GraphNode | None:
        return self._graph.by_fqn.get(fqn)

    def is_settled(self, fqn: str) -> bool:
        """Whether ``has_logger_services`` of that node can be believed yet.

        Services are discovered a little after their node: show an unsettled node without
        them as "checking", not as "no logger services".
        """
        graph = self._graph
        node = graph.by_fqn.get(fqn)
        return node is not None and graph.settled(node, self.clock())

    def find_node(self, query: str, wait: float) -> list[GraphNode]:
        """Blocking: the nodes ``query`` names (see ``match_nodes``), waiting up to ``wait`` s.

        Returns as soon as a match offers logger services, or has been seen for long enough
        to be sure it has none; at the deadline returns what matches (maybe nothing).
        """
        deadline = self.clock() + wait
        with self._graph_changed:
            while True:
                graph = self._graph
                matches = match_nodes(query, graph.nodes)
                now = self.clock()
                settled = any(graph.settled(node, now) for node in matches)
                if settled or now >= deadline or self._stop.is_set():
                    return matches
                self._graph_changed.wait(min(deadline - now, GRAPH_PERIOD_S))

    def wait_for_graph(self, seconds: float) -> tuple[GraphNode, ...]:
        """Blocking: the nodes after ``seconds`` of discovery (at least one graph look)."""
        deadline = self.clock() + seconds
        with self._graph_changed:
            while (self.clock() < deadline or self._graph.refreshes == 0) and not self._stop.is_set():
                self._graph_changed.wait(max(0.01, min(deadline - self.clock(), GRAPH_PERIOD_S)))
            return self._graph.nodes

    # -- calls ---------------------------------------------------------------------------------

    def get_levels(self, node: str, names: Iterable[str]) -> Future[dict[str, int]]:
        """The levels of ``names`` on ``node``: 0 for a logger with no level of its own."""
        from rcl_interfaces.srv import GetLoggerLevels

        names = list(names)
        request = GetLoggerLevels.Request(names=names)
        return _then(
            self._submit(node, GET_SERVICE, request), lambda response: {lv.name: lv.level for lv in response.levels}
        )

    def set_levels(self, node: str, levels: Mapping[str, int]) -> Future[dict[str, int]]:
        """Set levels (0 unsets a logger); the result is ``levels``. Ends their temporary levels."""

        def done(result: dict[str, int]) -> dict[str, int]:
            with self._lock:
                for name in result:
                    self._temporaries.cancel(node, name)
            return result

        return _then(self._set(node, levels), done)

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
            previous: Future[int] = _done(running.previous)
        else:
            previous = _then(self.get_levels(node, [logger]), lambda levels: levels.get(logger, 0))

        def register(before: int) -> TemporaryLevel:
            with self._lock:
                return self._temporaries.start(node, logger, level, before, seconds)

        return _then(previous, lambda before: _then(self._set(node, {logger: level}), lambda _: register(before)))

    def end_temporary(self, node: str, logger: str) -> Future[dict[str, int]]:
        """End a temporary level now, putting its previous level back (done at once if none runs)."""
        with self._lock:
            entry = self._temporaries.cancel(node, logger)
        if entry is None:
            return _done({})
        return self._restore(entry)

    def temporaries(self) -> tuple[TemporaryLevel, ...]:
        """The temporary levels running, soonest first. ``entry.remaining(control.clock())``."""
        with self._lock:
            return self._temporaries.pending()

    # -- internals: any thread ----------------------------------------------------------------

    def _set(self, node: str, levels: Mapping[str, int], *, restore: bool = False) -> Future[dict[str, int]]:
        from rcl_interfaces.msg import LoggerLevel
        from rcl_interfaces.srv import SetLoggerLevels

        levels = dict(levels)
        bad = {name: f"not a level: {level!r}" for name, level in levels.items() if not _is_level_number(level)}
        if levels.get(DEFAULT_LOGGER) == Severity.UNSET:
            # rcutils takes it, and the whole process then logs everything: never send it.
            bad[DEFAULT_LOGGER] = "the default logger cannot be unset"
        if bad:
            return _failed(LevelRefused(node, bad))
        request = SetLoggerLevels.Request(
            levels=[LoggerLevel(name=name, level=level) for name, level in levels.items()]
        )

        def check(response: Any) -> dict[str, int]:
            results = list(response.results)
            refused = {
                name: result.reason for name, result in zip(levels, results, strict=False) if not result.successful
            }
            # A reply with fewer results than levels asked for says nothing of the rest: not a success.
            refused.update({name: "the node's reply has no result for it" for name in list(levels)[len(results) :]})
            if refused:
                raise LevelRefused(node, refused)
            return levels

        return _then(self._submit(node, SET_SERVICE, request, restore), check)

    def _submit(self, node: str, service: str, request: Any, restore: bool = False) -> Future:
        future: Future = Future()
        call = _Call(node, service, request, self.clock() + self.call_timeout, future, restore)
        with self._lock:
            if self._closed:
                future.set_exception(ControlClosed(node))
                return future
            self._submitted.append(call)
        self._trigger()
        return future

    def _trigger(self) -> None:
        wake = self._wake
        if wake is not None:
            try:
                wake.trigger()
            except Exception:
                pass

    def _restore(self, entry: TemporaryLevel) -> Future[dict[str, int]]:
        return self._set(entry.node, {entry.logger: entry.previous}, restore=True)

    # -- internals: the loggers thread -------------------------------------------------------

    def _run(self) -> None:
        from rclpy.executors import SingleThreadedExecutor

        node: Any = None
        executor: Any = None
        calls: list[_Call] = []
        clients: dict[tuple[str, str], Any] = {}
        next_graph = started = self.clock()
        try:
            node = self.runtime.create_node("loggers")
            self._wake = node.create_guard_condition(lambda: None)
            executor = SingleThreadedExecutor(context=self.runtime.context)
            executor.add_node(node)
            while True:
                now = self.clock()
                if now >= next_graph:
                    next_graph = now + (STARTUP_GRAPH_PERIOD_S if now - started < STARTUP_S else GRAPH_PERIOD_S)
                    self._refresh_graph(node, clients, now)
                with self._lock:
                    new, self._submitted = self._submitted, []
                if any(call.node not in self._graph.by_fqn for call in new):
                    self._refresh_graph(node, clients, now)
                calls.extend(new)
                if self._stop.is_set() and not self._closed:
                    calls = self._begin_closing(calls)
                calls = [call for call in calls if not self._advance(node, clients, call, now)]
                if self._stop.is_set():
                    if not calls and not self._submitted:
                        break
                else:
                    self._restore_due()
                executor.spin_once(timeout_sec=self._idle_time(calls, next_graph))
        except Exception as error:  # the context went down under us, or a bug: say so, never hang
            if not self._stop.is_set():
                self.problem = f"logger levels stopped: {type(error).__name__}: {error}"
        finally:
            with self._lock:
                self._closed = True
                leftover, self._submitted = calls + self._submitted, []
            for call in leftover:
                _settle(call.future, error=ControlClosed(call.node))
            for closing in (executor and executor.shutdown, node and node.destroy_node):
                try:
                    if closing:
                        closing()
                except Exception:
                    pass

    def _idle_time(self, calls: list[_Call], next_graph: float) -> float:
        with self._lock:
            due = self._temporaries.next_deadline()
        wake = min([next_graph, *(call.deadline for call in calls), *([due] if due is not None else [])])
        return max(0.0, min(MAX_IDLE_S, wake - self.clock()))

    def _refresh_graph(self, node: Any, clients: dict[tuple[str, str], Any], now: float) -> None:
        services = node.get_service_names_and_types()
        with_services = frozenset(name.rpartition("/")[0] for name, _types in services)
        logger_services = {name for name, types in services if _logger_service(name, types)}
        found: dict[str, GraphNode] = {}
        for name, namespace in node.get_node_names_and_namespaces():
            if name.startswith(OWN_NODE_PREFIX):
                continue
            graph_node = GraphNode(namespace, name)
            if graph_node.hidden and not self.include_hidden:
                continue
            has = all(f"{graph_node.fqn}/{service}" in logger_services for service in _SERVICE_TYPES)
            found[graph_node.fqn] = GraphNode(namespace, name, has)
        nodes = tuple(sorted(found.values(), key=lambda n: n.fqn))
        with self._graph_changed:
            old = self._graph
            first_seen = {fqn: old.first_seen.get(fqn, now) for fqn in found}
            self._graph = _Graph(nodes, found, first_seen, with_services, old.refreshes + 1)
            self._graph_changed.notify_all()
        for key in [key for key in clients if key[0] not in found]:
            try:
                node.destroy_client(clients.pop(key))
            except Exception:
                pass
        if nodes != old.nodes:
            self._emit(NodesChanged(nodes))

    def _advance(self, node: Any, clients: dict[tuple[str, str], Any], call: _Call, now: float) -> bool:
        """Move one call on; True once its future is settled."""
        if call.future.done():
            return True
        graph_node = self._graph.by_fqn.get(call.node)
        if call.sent is None:
            if graph_node is None:
                return _settle(call.future, error=NodeNotFound(call.node))
            if not graph_node.has_logger_services and (self._graph.settled(graph_node, now) or now >= call.deadline):
                return _settle(call.future, error=NoLoggerServices(call.node))
            if graph_node.has_logger_services:
                client = clients.get((call.node, call.service))
                if client is None:
                    client = node.create_client(_service_type(call.service), f"{call.node}/{call.service}")
                    clients[(call.node, call.service)] = client
                if client.service_is_ready():
                    call.client = client
                    call.sent = client.call_async(call.request)
                    return False
            if now >= call.deadline:
                return _settle(call.future, error=CallTimedOut(call.node, self.call_timeout))
            return False
        if call.sent.done():
            error = call.sent.exception()
            if error is not None:
                return _settle(call.future, error=LoggerCallError(call.node, f"{call.node}: {error}"))
            return _settle(call.future, result=call.sent.result())
        if graph_node is None or not call.client.service_is_ready():
            call.client.remove_pending_request(call.sent)
            return _settle(call.future, error=NodeGone(call.node))
        if now >= call.deadline:
            call.client.remove_pending_request(call.sent)
            return _settle(call.future, error=CallTimedOut(call.node, self.call_timeout))
        return False

    def _restore_due(self) -> None:
        with self._lock:
            due = self._temporaries.take_due()
        for entry in due:
            self._restore(entry).add_done_callback(lambda future, entry=entry: self._restored(entry, future))

    def _restored(self, entry: TemporaryLevel, future: Future) -> None:
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
        if error is not None and not isinstance(error, LoggerCallError):
            error = LoggerCallError(entry.node, f"{entry.node}: {error}")
        self._emit(TemporaryEnded(entry, error))

    def _begin_closing(self, calls: list[_Call]) -> list[_Call]:
        """Fail the calls under way, and put every temporary level back; returns the calls left."""
        with self._lock:
            entries = self._temporaries.take_all()
        for call in calls:
            if not call.restore:
                if call.client is not None and call.sent is not None:
                    call.client.remove_pending_request(call.sent)
                _settle(call.future, error=ControlClosed(call.node))
        for entry in entries:
            self._restore(entry).add_done_callback(
                lambda future, entry=entry: self._emit(TemporaryEnded(entry, future.exception()))
            )
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


def _is_level_number(level: Any) -> bool:
    return isinstance(level, int) and 0 <= level < 2**32


def _logger_service(name: str, types: list[str]) -> bool:
    suffix = name.rpartition("/")[2]
    return _SERVICE_TYPES.get(suffix) in types


def _service_type(service: str) -> Any:
    from rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels

    return GetLoggerLevels if service == GET_SERVICE else SetLoggerLevels


# -- futures -------------------------------------------------------------------------------


def _settle(future: Future, *, result: Any = None, error: BaseException | None = None) -> bool:
    if not future.done():
        if error is not None:
            future.set_exception(error)
        else:
            future.set_result(result)
    return True


def _done(value: T) -> Future[T]:
    future: Future[T] = Future()
    future.set_result(value)
    return future


def _failed(error: BaseException) -> Future:
    future: Future = Future()
    future.set_exception(error)
    return future


def _then(source: Future, step: Callable[[Any], Any]) -> Future:
    """A future of ``step(source's result)``; a step returning a future is followed through."""
    out: Future = Future()

    def follow(inner: Future) -> None:
        error = inner.exception()
        _settle(out, result=None if error else inner.result(), error=error)

    def done(finished: Future) -> None:
        error = finished.exception()
        if error is not None:
            _settle(out, error=error)
            return
        try:
            value = step(finished.result())
        except Exception as failure:
            _settle(out, error=failure)
            return
        if isinstance(value, Future):
            value.add_done_callback(follow)
        else:
            _settle(out, result=value)

    source.add_done_callback(done)
    return out
