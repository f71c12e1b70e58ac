"""XML-RPC calls to the ROS 1 master and to nodes' slave APIs, each with a timeout.

Every ROS 1 API call answers ``[code, status message, value]``; code 1 is success. A call
that fails in any way (no answer in time, connection refused, garbage, a code other than
1) raises ``Ros1CallError`` whose text names the URI and says what went wrong. A fresh
connection is made per call, so calls may come from any thread.
"""

from __future__ import annotations

import http.client
import xmlrpc.client
from typing import Any
from xml.parsers.expat import ExpatError

CALL_TIMEOUT_S = 2.0
#: How long to wait for a master when deciding between ROS 1 and ROS 2.
PROBE_TIMEOUT_S = 0.8


class Ros1CallError(Exception):
    """An XML-RPC call failed; ``str()`` says which URI and why, ``reason`` just why."""

    def __init__(self, uri: str, reason: str, *, unreachable: bool = False) -> None:
        super().__init__(f"{uri}: {reason}")
        self.uri = uri
        self.reason = reason
        #: No answer at all (refused, timed out, not XML-RPC), rather than an answer saying no.
        self.unreachable = unreachable


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout: float) -> None:
        super().__init__()
        self._timeout = timeout

    def make_connection(self, host: Any) -> http.client.HTTPConnection:
        connection = super().make_connection(host)
        connection.timeout = self._timeout
        return connection


class _ServerNamingTransport(_TimeoutTransport):
    """Keeps the ``Server`` header of the last answer: the software behind a slave API."""

    server = ""

    def parse_response(self, response: http.client.HTTPResponse) -> Any:
        self.server = response.getheader("Server") or ""
        return super().parse_response(response)


def xmlrpc_call(
    uri: str, method: str, *args: Any, timeout: float = CALL_TIMEOUT_S, transport: _TimeoutTransport | None = None
) -> Any:
    """``method(*args)`` at ``uri``; the value of a code-1 answer, else ``Ros1CallError``."""
    proxy = xmlrpc.client.ServerProxy(uri, transport=transport or _TimeoutTransport(timeout))
    try:
        answer = getattr(proxy, method)(*args)
    except TimeoutError:
        raise Ros1CallError(uri, f"no answer within {timeout:g} s", unreachable=True) from None
    except ConnectionRefusedError:
        raise Ros1CallError(uri, "connection refused (nothing listens there)", unreachable=True) from None
    except (OSError, http.client.HTTPException, xmlrpc.client.ProtocolError, ExpatError, ValueError) as error:
        raise Ros1CallError(uri, f"{method} failed: {_reason(error)}", unreachable=True) from None
    except xmlrpc.client.Fault as fault:
        raise Ros1CallError(uri, f"{method} failed: {fault.faultString}") from None
    if not isinstance(answer, (list, tuple)) or len(answer) != 3:
        raise Ros1CallError(uri, f"{method} gave an answer that is not [code, message, value]")
    code, message, value = answer
    if code != 1:
        raise Ros1CallError(uri, f"{method}: {message or 'failed'} (code {code})")
    return value


#: A node's client library, told by the ``Server`` header its slave API answers with.
ROSCPP = "roscpp"
ROSPY = "rospy"


def client_library(uri: str, caller_id: str, timeout: float = CALL_TIMEOUT_S) -> str | None:
    """Which client library serves the slave API at ``uri``: roscpp (its xmlrpcpp answers as
    ``XMLRPC++``), rospy (Python's ``BaseHTTP``), None for anything else; ``Ros1CallError``."""
    transport = _ServerNamingTransport(timeout)
    xmlrpc_call(uri, "getPid", caller_id, timeout=timeout, transport=transport)
    if transport.server.startswith("XMLRPC++"):
        return ROSCPP
    if transport.server.startswith("BaseHTTP/"):
        return ROSPY
    return None


def _reason(error: BaseException) -> str:
    text = str(error) or type(error).__name__
    if isinstance(error, OSError) and error.strerror:
        text = error.strerror
    return text


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
        return [str(uri) for uri in self._call("registerSubscriber", topic, topic_type, caller_api)]

    def unregister_subscriber(self, topic: str, caller_api: str) -> None:
        self._call("unregisterSubscriber", topic, caller_api)

    def system_state(self) -> SystemState:
        publishers, subscribers, services = self._call("getSystemState")
        return SystemState(_table(publishers), _table(subscribers), _table(services))

    def lookup_node(self, node: str) -> str:
        return str(self._call("lookupNode", node))

    def lookup_service(self, service: str) -> str:
        return str(self._call("lookupService", service))

    def run_id(self) -> str:
        """The master's ``/run_id`` parameter ("" when it has none, as a bare rosmaster)."""
        try:
            return str(self._call("getParam", "/run_id"))
        except Ros1CallError as error:
            if error.unreachable:
                raise
            return ""

    def pid(self) -> int:
        return int(self._call("getPid"))


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
    for row in rows or ():
        if isinstance(row, (list, tuple)) and len(row) == 2:
            table[str(row[0])] = [str(name) for name in row[1]]
    return table


def probe_master(uri: str, timeout: float = PROBE_TIMEOUT_S) -> bool:
    """Whether a ROS 1 master answers at ``uri`` within ``timeout``."""
    try:
        xmlrpc_call(uri, "getUri", "/console_tui_probe", timeout=timeout)
    except Ros1CallError:
        return False
    return True
