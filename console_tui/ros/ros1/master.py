"""The ROS 1 master's API as console-tui uses it, each call bounded (``xmlrpc.py``).

An answer of the wrong shape (a pid that is not a number, a list that is not one) raises
``Ros1CallError`` like any failed call: a problem of that call, said and tried again.
"""

from __future__ import annotations

from typing import Any

from .xmlrpc import CALL_TIMEOUT_S, Ros1CallError, malformed, xmlrpc_call

__all__ = ["CALL_TIMEOUT_S", "Master", "Ros1CallError", "SystemState", "probe_master", "xmlrpc_call"]

#: How long to wait for a master when deciding between ROS 1 and ROS 2.
PROBE_TIMEOUT_S = 0.8


#: A node's client library, told by the ``Server`` header its slave API answers with.
ROSCPP = "roscpp"
ROSPY = "rospy"


def client_library(uri: str, caller_id: str, timeout: float = CALL_TIMEOUT_S) -> str | None:
    """Which client library serves the slave API at ``uri``: roscpp (its xmlrpcpp answers as
    ``XMLRPC++``), rospy (Python's ``BaseHTTP``), None for anything else; ``Ros1CallError``."""
    server: list[str] = []
    xmlrpc_call(uri, "getPid", caller_id, timeout=timeout, answered_by=server)
    name = server[0] if server else ""
    if name.startswith("XMLRPC++"):
        return ROSCPP
    if name.startswith("BaseHTTP/"):
        return ROSPY
    return None


class Master:
    """The master's API, called as node ``caller_id``."""

    def __init__(self, uri: str, caller_id: str, timeout: float = CALL_TIMEOUT_S) -> None:
        self.uri = uri
        self.caller_id = caller_id
        self.timeout = timeout

    def _call(self, method: str, *args: Any) -> Any:
        return xmlrpc_call(self.uri, method, self.caller_id, *args, timeout=self.timeout)

    def register_subscriber(self, topic: str, topic_type: str, caller_api: str) -> list[str]:
        """Subscribe; returns the slave URIs of the topic's publishers."""
        uris = self._call("registerSubscriber", topic, topic_type, caller_api)
        if not isinstance(uris, (list, tuple)) or not all(isinstance(uri, str) for uri in uris):
            raise malformed(self.uri, "registerSubscriber", uris)
        return list(uris)

    def unregister_subscriber(self, topic: str, caller_api: str) -> None:
        self._call("unregisterSubscriber", topic, caller_api)

    def system_state(self) -> SystemState:
        state = self._call("getSystemState")
        if not isinstance(state, (list, tuple)) or len(state) != 3:
            raise malformed(self.uri, "getSystemState", state)
        publishers, subscribers, services = state
        return SystemState(_table(publishers), _table(subscribers), _table(services))

    def lookup_node(self, node: str) -> str:
        return self._text("lookupNode", node)

    def lookup_service(self, service: str) -> str:
        return self._text("lookupService", service)

    def _text(self, method: str, *args: Any) -> str:
        value = self._call(method, *args)
        if not isinstance(value, str):
            raise malformed(self.uri, method, value)
        return value

    def run_id(self) -> str:
        """The master's ``/run_id`` parameter ("" when it has none, as a bare rosmaster)."""
        try:
            return str(self._call("getParam", "/run_id"))
        except Ros1CallError as error:
            if error.unreachable:
                raise
            return ""

    def pid(self) -> int:
        pid = self._call("getPid")
        if not isinstance(pid, int) or isinstance(pid, bool):
            raise malformed(self.uri, "getPid", pid)
        return pid


class SystemState:
    """The master's view of the graph: topic -> publishing nodes, topic -> subscribing
    nodes, service -> providing nodes."""

    __slots__ = ("publishers", "services", "subscribers")

    def __init__(
        self, publishers: dict[str, list[str]], subscribers: dict[str, list[str]], services: dict[str, list[str]]
    ) -> None:
        self.publishers = publishers
        self.subscribers = subscribers
        self.services = services

    def nodes(self) -> set[str]:
        """Every node named anywhere in the state."""
        return {
            node
            for table in (self.publishers, self.subscribers, self.services)
            for names in table.values()
            for node in names
        }


def _table(rows: Any) -> dict[str, list[str]]:
    table: dict[str, list[str]] = {}
    for row in rows if isinstance(rows, (list, tuple)) else ():
        if isinstance(row, (list, tuple)) and len(row) == 2 and isinstance(row[1], (list, tuple)):
            table[str(row[0])] = [str(name) for name in row[1]]
    return table


def probe_master(uri: str, timeout: float = PROBE_TIMEOUT_S) -> bool:
    """Whether a ROS 1 master answers at ``uri`` within ``timeout``."""
    try:
        xmlrpc_call(uri, "getUri", "/console_tui_probe", timeout=timeout)
    except Ros1CallError:
        return False
    return True
