"""ROS 2 logger levels: the nodes' ``get_logger_levels`` / ``set_logger_levels`` services.

``Ros2LoggerControl`` is the ROS 2 side of ``control.control_thread.LoggerControl`` (which says
what the control promises): its loggers thread owns a hidden node, the service clients and an
executor, and every rclpy call happens there.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from concurrent.futures import Future
from typing import Any

from ...model.loggers.logger_levels import ENABLE_LOGGER_SERVICE_HINT, GraphNode
from ...ros.ros2.runtime import RosRuntime
from ..calls import GET, SET, Call
from ..control_thread import CALL_TIMEOUT_S, LoggerControl
from ..errors import LevelRefused
from ..futures import then

_SERVICES = {GET: "get_logger_levels", SET: "set_logger_levels"}
_SERVICE_TYPES = {
    "get_logger_levels": "rcl_interfaces/srv/GetLoggerLevels",
    "set_logger_levels": "rcl_interfaces/srv/SetLoggerLevels",
}


class Ros2LoggerControl(LoggerControl):
    """Lists a ROS 2 graph's nodes and gets and sets their logger levels, off the caller's thread."""

    no_services_hint = ENABLE_LOGGER_SERVICE_HINT

    def __init__(
        self,
        runtime: RosRuntime,
        *,
        call_timeout: float = CALL_TIMEOUT_S,
        include_hidden: bool = False,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        super().__init__(call_timeout=call_timeout, include_hidden=include_hidden, clock=clock)
        self.runtime = runtime
        self._node: Any = None
        self._executor: Any = None
        self._guard: Any = None
        self._clients: dict[tuple[str, str], Any] = {}

    # -- requests and replies: any thread ------------------------------------------------------

    def _call_get(self, node: str, names: list[str]) -> Future[dict[str, int]]:
        from rcl_interfaces.srv import GetLoggerLevels

        request = GetLoggerLevels.Request(names=names)
        return then(self._submit(node, GET, request), lambda response: {lv.name: lv.level for lv in response.levels})

    def _call_set(self, node: str, levels: dict[str, int], *, restore: bool) -> Future[dict[str, int]]:
        from rcl_interfaces.msg import LoggerLevel
        from rcl_interfaces.srv import SetLoggerLevels

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

        return then(self._submit(node, SET, request, restore), check)

    def _wake(self) -> None:
        guard = self._guard
        if guard is not None:
            guard.trigger()

    # -- the loggers thread ----------------------------------------------------------------------

    def _open(self) -> None:
        from rclpy.executors import SingleThreadedExecutor

        self._node = self.runtime.create_node("loggers")
        self._guard = self._node.create_guard_condition(lambda: None)
        self._executor = SingleThreadedExecutor(context=self.runtime.context)
        self._executor.add_node(self._node)

    def _wait(self, timeout: float) -> None:
        self._executor.spin_once(timeout_sec=timeout)

    def _look(self) -> tuple[Iterable[GraphNode], frozenset[str]]:
        node = self._node
        services = node.get_service_names_and_types()
        with_services = frozenset(name.rpartition("/")[0] for name, _types in services)
        logger_services = {name for name, types in services if _logger_service(name, types)}
        found = []
        for name, namespace in node.get_node_names_and_namespaces():
            fqn = GraphNode(namespace, name).fqn
            has = all(f"{fqn}/{service}" in logger_services for service in _SERVICE_TYPES)
            found.append(GraphNode(namespace, name, has))
        present = {graph_node.fqn for graph_node in found}
        for key in [key for key in self._clients if key[0] not in present]:
            try:
                node.destroy_client(self._clients.pop(key))
            except Exception:
                pass
        return found, with_services

    def _send(self, call: Call) -> Any:
        key = (call.node, call.service)
        client = self._clients.get(key)
        if client is None:
            service = _SERVICES[call.service]
            client = self._node.create_client(_service_type(service), f"{call.node}/{service}")
            self._clients[key] = client
        if not client.service_is_ready():
            return None
        call.handle = client
        return client.call_async(call.request)

    def _lost(self, call: Call) -> bool:
        return not call.handle.service_is_ready()

    def _drop(self, call: Call) -> None:
        if call.handle is not None and call.sent is not None:
            call.handle.remove_pending_request(call.sent)

    def _shutdown(self) -> None:
        for closing in (self._executor and self._executor.shutdown, self._node and self._node.destroy_node):
            try:
                if closing:
                    closing()
            except Exception:
                pass


def _logger_service(name: str, types: list[str]) -> bool:
    suffix = name.rpartition("/")[2]
    return _SERVICE_TYPES.get(suffix) in types


def _service_type(service: str) -> Any:
    from rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels

    return GetLoggerLevels if service == "get_logger_levels" else SetLoggerLevels
