"""ROS 1 logger levels: every node's ``~get_loggers`` and ``~set_logger_level``, natively.

``Ros1LoggerControl`` is the ROS 1 side of ``control.control_thread.LoggerControl``. The
nodes come from the master's system state (a node offering both services has the logger
services: every roscpp and rospy node). A read calls the node's ``get_loggers``, which
lists all its loggers with their levels in force; a set calls ``set_logger_level`` once
per logger, the level as a word. ROS 1 loggers cannot be unset.

Hazard: on Debian 12 (rosconsole with log4cxx 1.x) ``get_loggers`` can crash a roscpp node
(SIGSEGV; ``rosservice call`` does it too). So nothing here reads levels on its own: the
UI reads a node only when the user asks, and when the node drops the call the error says
what may have happened; levels can still be set by typing a logger's name.

Service calls block (XML-RPC to the master, TCPROS to the node), so they run on a small
pool of worker threads, each step with the call's timeout.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any

from ...model.levels import Severity
from ...model.loggers.logger_levels import GraphNode, effective_level, split_fqn
from ...ros.ros1.environment import NODE_PREFIX, Ros1Environment, new_node_name
from ...ros.ros1.master import ROSCPP, ROSPY, Master, Ros1CallError, client_library
from ...ros.ros1.tcpros import ServiceFailed, TcprosError, call_service
from ..calls import GET, SET, Call
from ..control_thread import CALL_TIMEOUT_S, LoggerControl
from ..errors import LevelRefused, LoggerCallError
from ..futures import failed_future, then
from .logger_services import (
    GET_LOGGERS,
    GET_LOGGERS_MD5,
    LEVEL_WORDS,
    SET_LOGGER_LEVEL,
    SET_LOGGER_LEVEL_MD5,
    ReplyError,
    decode_loggers,
    encode_set_level,
    level_of_word,
)

NO_SERVICES_HINT = "only roscpp and rospy nodes offer ~get_loggers and ~set_logger_level"
#: The logger a node's own messages go through, by its client library: rospy logs through
#: ``rosout``; roscpp through ``ros.<package>``, whose parent ``ros`` has the level in force.
OWN_LOGGER = {ROSPY: "rosout", ROSCPP: "ros"}
WORKERS = 4
#: After a failed look at the graph (a master refusing, or sending what is refused), the next
#: comes this much later, doubling up to the most: a hostile master costs little.
LOOK_RETRY_FIRST_S = 1.0
LOOK_RETRY_MAX_S = 30.0
_SERVICE = {GET: GET_LOGGERS, SET: SET_LOGGER_LEVEL}
_MD5 = {GET: GET_LOGGERS_MD5, SET: SET_LOGGER_LEVEL_MD5}


class Ros1LoggerControl(LoggerControl):
    """Lists a ROS 1 master's nodes and gets and sets their logger levels, off the caller's thread."""

    no_services_hint = NO_SERVICES_HINT
    #: The master knows the whole graph at once: nothing to wait for.
    graph_min_s = 0.0
    graph_quiet_s = 0.0
    lists_loggers = True
    read_when_asked = True
    #: The graph is the master's ``getSystemState``: asked only while someone looks.
    remote_graph = True

    def __init__(
        self,
        environment: Ros1Environment | None = None,
        *,
        call_timeout: float = CALL_TIMEOUT_S,
        include_hidden: bool = False,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        super().__init__(call_timeout=call_timeout, include_hidden=include_hidden, clock=clock)
        self.environment = environment or Ros1Environment.from_environ()
        self.caller_id = new_node_name()
        self._master = Master(self.environment.master_uri, self.caller_id, call_timeout)
        self._pool: ThreadPoolExecutor | None = None
        self._last_look: tuple[list[GraphNode], frozenset[str]] = ([], frozenset())
        self._look_after = 0.0
        self._look_backoff = 0.0

    # -- requests and replies: any thread --------------------------------------------------------

    def _call_get(self, node: str, names: list[str]) -> Future[dict[str, int]]:
        def levels(loggers: list[tuple[str, str]]) -> dict[str, int]:
            found = {name: level for name, word in loggers if (level := level_of_word(word)) is not None}
            # Names asked for that the node does not list log at their nearest listed ancestor's level.
            for name in names:
                if name not in found:
                    inherited = effective_level(name, found)
                    if inherited is not None:
                        found[name] = inherited
            return found

        return then(self._submit(node, GET, None), levels)

    def _call_set(self, node: str, levels: dict[str, int], *, restore: bool) -> Future[dict[str, int]]:
        bad = {}
        for name, level in levels.items():
            if level == Severity.UNSET:
                bad[name] = "ROS 1 loggers cannot be unset: give a level"
            elif level not in LEVEL_WORDS:
                bad[name] = f"not a ROS 1 level: {level}"
        if bad:
            return failed_future(LevelRefused(node, bad))
        request = [(name, LEVEL_WORDS[level]) for name, level in levels.items()]
        return then(self._submit(node, SET, request, restore), lambda _reply: levels)

    def own_logger(self, node: str) -> str:
        """The logger ``node``'s own messages go through (``OWN_LOGGER``), told by the server
        software of its slave API: no ``get_loggers`` call, which can crash roscpp nodes.
        Blocks for at most two calls' timeouts; ``LoggerCallError`` when it cannot tell."""
        try:
            library = client_library(self._master.lookup_node(node), self.caller_id, self.call_timeout)
        except Ros1CallError as error:
            raise LoggerCallError(node, f"{node}: cannot tell its client library ({error.reason})") from None
        if library is None:
            raise LoggerCallError(
                node,
                f"{node} is neither a roscpp nor a rospy node: name the logger "
                f"('console-tui loggers get {node}' lists them)",
            )
        return OWN_LOGGER[library]

    # -- the loggers thread ----------------------------------------------------------------------

    def _open(self) -> None:
        self._pool = ThreadPoolExecutor(WORKERS, thread_name_prefix="console-tui-ros1-loggers")

    def _look(self) -> tuple[Iterable[GraphNode], frozenset[str]]:
        now = self.clock()
        if now < self._look_after:  # the last look failed: the master is asked again later
            return self._last_look
        try:
            state = self._master.system_state()
        except Ros1CallError as error:
            if error.unreachable:
                self.problem = f"waiting for master at {self.environment.master_uri}: {error.reason}"
            else:
                self.problem = f"the master at {self.environment.master_uri}: {error.reason}"
            self._look_backoff = min(self._look_backoff * 2 or LOOK_RETRY_FIRST_S, LOOK_RETRY_MAX_S)
            self._look_after = self.clock() + self._look_backoff
            return self._last_look
        self._look_backoff = 0.0
        self.problem = ""
        providers: dict[str, set[str]] = {}
        for service, names in state.services.items():
            for name in names:
                providers.setdefault(name, set()).add(service)
        found = []
        for fqn in sorted(state.nodes()):
            if fqn.startswith(NODE_PREFIX):
                continue
            offered = providers.get(fqn, set())
            has = f"{fqn}/{GET_LOGGERS}" in offered and f"{fqn}/{SET_LOGGER_LEVEL}" in offered
            namespace, name = split_fqn(fqn)
            found.append(GraphNode(namespace, name, has))
        self._last_look = (found, frozenset(providers))
        return self._last_look

    def _send(self, call: Call) -> Any:
        assert self._pool is not None
        return self._pool.submit(self._exchange, call)

    def _drop(self, call: Call) -> None:
        pass  # a blocking call ends by its own timeout; its late result is ignored

    def _shutdown(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=False, cancel_futures=True)

    # -- on a worker thread ----------------------------------------------------------------------

    def _exchange(self, call: Call) -> Any:
        """Look the service up and call it; raises ``LoggerCallError`` with the text to show."""
        node = call.node
        service = f"{node}/{_SERVICE[call.service]}"
        try:
            uri = self._master.lookup_service(service)
        except Ros1CallError as error:
            raise LoggerCallError(node, f"{node}: the master does not know {service} ({error.reason})") from None
        if call.service == GET:
            body = self._call(call, uri, service, b"")
            try:
                return decode_loggers(body)
            except ReplyError as error:
                raise LoggerCallError(node, f"{node}: {error}") from None
        for logger, word in call.request:
            try:
                self._call(call, uri, service, encode_set_level(logger, word))
            except ServiceFailed as failure:
                reason = str(failure) or f"no reason given: is {word!r} a level this node knows?"
                raise LevelRefused(node, {logger: reason}) from None
        return None

    def _call(self, call: Call, uri: str, service: str, request: bytes) -> bytes:
        node = call.node
        left = call.deadline - self.clock()
        if left <= 0:
            raise LoggerCallError(node, f"{node} did not answer within {self.call_timeout:g} s")
        try:
            return call_service(uri, service, _MD5[call.service], request, caller_id=self.caller_id, timeout=left)
        except ServiceFailed:
            raise
        except TcprosError as error:
            raise LoggerCallError(node, _explain(node, call.service, str(error))) from None


def _explain(node: str, service: str, reason: str) -> str:
    if "refused the connection" in reason:
        return (
            f"{node} does not answer (connection refused): the node is gone; "
            "a killed node stays registered with the master until 'rosnode cleanup'"
        )
    if service == GET and "closed" in reason:
        return (
            f"{node} dropped the get_loggers call ({reason}): roscpp nodes with log4cxx 1.x (Debian 12) "
            "crash there, so the node may be gone; levels can still be set by typing a logger's name (a)"
        )
    return f"{node}: {reason}"
