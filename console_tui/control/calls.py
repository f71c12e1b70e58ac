"""One logger-level call as the loggers thread moves it on: sent, answered, timed out or gone.

A ``Call`` is queued by ``LoggerControl._submit`` from any thread; the loggers thread calls
``Call.advance`` on every pass until the call's future is settled. How a call goes out and
is dropped is the ROS's own (``LoggerControl._send``, ``_drop``, ``_lost``).
"""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import Future
from dataclasses import dataclass
from typing import Any

from .errors import CallTimedOut, LoggerCallError, NodeGone, NodeNotFound, call_error
from .futures import settle
from .graph import GraphSnapshot

GET = "get"
SET = "set"


@dataclass
class Call:
    """A call submitted to a node's logger service, as the loggers thread moves it on."""

    node: str
    #: ``GET`` or ``SET``.
    service: str
    request: Any
    deadline: float
    future: Future[Any]
    #: Puts a temporary level back: still sent while closing.
    restore: bool = False
    #: The subclass's own state for the call (its client, say).
    handle: Any = None
    #: What ``_send`` returned: the reply to come.
    sent: Any = None

    def advance(
        self,
        now: float,
        graph: GraphSnapshot,
        *,
        send: Callable[[Call], Any],
        drop: Callable[[Call], None],
        lost: Callable[[Call], bool],
        no_services: Callable[[str], LoggerCallError],
        timeout: float,
    ) -> bool:
        """Move the call on; True once its future is settled."""
        if self.future.done():
            return True
        graph_node = graph.by_fqn.get(self.node)
        if self.sent is None:
            if graph_node is None:
                return settle(self.future, error=NodeNotFound(self.node))
            if not graph_node.has_logger_services and (graph.settled(graph_node, now) or now >= self.deadline):
                return settle(self.future, error=no_services(self.node))
            if graph_node.has_logger_services:
                self.sent = send(self)
                if self.sent is not None:
                    return False
            if now >= self.deadline:
                return settle(self.future, error=CallTimedOut(self.node, timeout))
            return False
        if self.sent.done():
            error = self.sent.exception()
            if error is not None:
                return settle(self.future, error=call_error(self.node, error))
            return settle(self.future, result=self.sent.result())
        if graph_node is None or lost(self):
            drop(self)
            return settle(self.future, error=NodeGone(self.node))
        if now >= self.deadline:
            drop(self)
            return settle(self.future, error=CallTimedOut(self.node, timeout))
        return False
