"""Our node's slave API: the XML-RPC server the master and tools call us on.

What is called here (checked against Debian's roscore and tools): ``publisherUpdate``
(the master, when a topic's publishers change), ``getPid`` (``rosnode ping``, ``info``,
``cleanup``), ``getBusInfo`` (``rosnode info``), ``shutdown`` (``rosnode kill``, or a node
of the same name starting). The rest of the API answers too: ``getBusStats``,
``getMasterUri``, ``getSubscriptions``, ``getPublications`` (none), ``paramUpdate``,
``requestTopic`` (we publish nothing, so it says so).

The server runs in a thread of its own; each request gets a short-lived thread, so a
slow caller holds up nobody. Nothing is printed: a TUI owns the terminal.
"""

from __future__ import annotations

import os
import socketserver
import threading
from typing import Any, Protocol
from xmlrpc.server import SimpleXMLRPCRequestHandler, SimpleXMLRPCServer

from .environment import Ros1Environment

POLL_S = 0.1


class SlaveNode(Protocol):
    """What the slave API asks of the node it serves; called on the server's threads."""

    def bus_info(self) -> list[list[Any]]:
        """``[connection id, peer, 'i', 'TCPROS', topic, connected, info]`` per connection."""
        ...

    def bus_stats(self) -> list[list[Any]]:
        """``[topic, [[connection id, bytes received, drop estimate, connected], ...]]`` per topic."""
        ...

    def subscriptions(self) -> list[list[str]]:
        """``[topic, type]`` per subscribed topic."""
        ...

    def publisher_update(self, topic: str, publishers: list[str]) -> None: ...

    def shutdown_requested(self, caller_id: str, reason: str) -> None: ...


class _QuietHandler(SimpleXMLRPCRequestHandler):
    rpc_paths = ()  # any path: some tools add one

    def log_message(self, format: str, *args: Any) -> None:
        pass


class _Server(socketserver.ThreadingMixIn, SimpleXMLRPCServer):
    daemon_threads = True
    allow_reuse_address = True

    def handle_error(self, request: Any, client_address: Any) -> None:
        pass  # a caller that went away mid-request: nothing to tell anyone


class SlaveServer:
    """Serves the slave API of ``node`` at ``uri`` (``http://ADVERTISED:PORT/``)."""

    def __init__(self, environment: Ros1Environment, node: SlaveNode) -> None:
        self.environment = environment
        self.node = node
        self._server = _Server((environment.bind, 0), requestHandler=_QuietHandler, logRequests=False, allow_none=False)
        port = self._server.server_address[1]
        self.uri = f"http://{_url_host(environment.advertise)}:{port}/"
        for name in (
            "getBusStats",
            "getBusInfo",
            "getMasterUri",
            "shutdown",
            "getPid",
            "getSubscriptions",
            "getPublications",
            "paramUpdate",
            "publisherUpdate",
            "requestTopic",
        ):
            self._server.register_function(getattr(self, name), name)
        self._thread: threading.Thread | None = None

    def start(self) -> None:
        self._thread = threading.Thread(
            target=self._server.serve_forever, args=(POLL_S,), name="console-tui-ros1-slave", daemon=True
        )
        self._thread.start()

    def close(self) -> None:
        if self._thread is not None:
            self._server.shutdown()
            self._thread.join(2.0)
        self._server.server_close()

    # -- the API: every call answers [code, status message, value] ---------------------------

    def getBusStats(self, caller_id: str) -> list[Any]:
        return [1, "", [[], self.node.bus_stats(), []]]

    def getBusInfo(self, caller_id: str) -> list[Any]:
        return [1, "bus info", self.node.bus_info()]

    def getMasterUri(self, caller_id: str) -> list[Any]:
        return [1, "", self.environment.master_uri]

    def shutdown(self, caller_id: str, msg: str = "") -> list[Any]:
        self.node.shutdown_requested(str(caller_id), str(msg))
        return [1, "shutdown", 0]

    def getPid(self, caller_id: str) -> list[Any]:
        return [1, "", os.getpid()]

    def getSubscriptions(self, caller_id: str) -> list[Any]:
        return [1, "subscriptions", self.node.subscriptions()]

    def getPublications(self, caller_id: str) -> list[Any]:
        return [1, "publications", []]

    def paramUpdate(self, caller_id: str, key: str, value: Any) -> list[Any]:
        return [1, "", 0]

    def publisherUpdate(self, caller_id: str, topic: str, publishers: list[str]) -> list[Any]:
        self.node.publisher_update(str(topic), [str(uri) for uri in publishers])
        return [1, "", 0]

    def requestTopic(self, caller_id: str, topic: str, protocols: list[Any]) -> list[Any]:
        return [0, f"not a publisher of [{topic}]", []]


def _url_host(host: str) -> str:
    return f"[{host}]" if ":" in host and not host.startswith("[") else host
