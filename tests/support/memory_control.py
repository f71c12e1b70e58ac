"""A logger control over an in-memory graph of nodes (no ROS): ``MemoryControl`` is the
smallest subclass ``LoggerControl`` accepts, and shows what a ROS provides. For tests of
what the control and the app do with it; ROS 2's own is tested against real nodes.
``running`` starts any of them for a test, ``StepClock`` is a clock the test moves."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from concurrent.futures import Future

from console_tui.control.calls import GET, SET
from console_tui.control.control_thread import LoggerControl
from console_tui.control.errors import LevelRefused
from console_tui.control.futures import done_future, failed_future, then
from console_tui.model.loggers.logger_levels import GraphNode, split_fqn


class MemoryNode:
    def __init__(self, fqn: str, services: bool = True) -> None:
        self.fqn = fqn
        self.services = services
        self.levels: dict[str, int] = {"": 20}
        #: While set, calls wait for it (a busy node).
        self.busy: threading.Event | None = None


class MemoryControl(LoggerControl):
    no_services_hint = "give it some"

    def __init__(self, nodes: list[MemoryNode], **kwargs) -> None:
        super().__init__(**kwargs)
        self.graph = {node.fqn: node for node in nodes}
        self.dropped: list[str] = []
        self.shut = False

    def _open(self) -> None:
        pass

    def _look(self):
        return [GraphNode(*split_fqn(fqn), node.services) for fqn, node in self.graph.items()], frozenset()

    def _call_get(self, node, names):
        return then(self._submit(node, GET, names), lambda levels: {name: levels.get(name, 0) for name in names})

    def _call_set(self, node, levels, *, restore):
        if any(level % 10 for level in levels.values()):
            return failed_future(LevelRefused(node, {name: "odd level" for name in levels}))
        return then(self._submit(node, SET, levels, restore), lambda _: levels)

    def _send(self, call):
        node = self.graph[call.node]
        if node.busy is not None:
            return Future()  # never answers
        if call.service == SET:
            node.levels.update(call.request)
        return done_future(dict(node.levels))

    def _drop(self, call):
        self.dropped.append(call.node)

    def _shutdown(self) -> None:
        self.shut = True


def running(control: LoggerControl) -> Iterator[LoggerControl]:
    """For a fixture (``yield from``): ``control`` started, every event it sends kept in
    ``control.events``; closed at the end."""
    control.events = []  # type: ignore[attr-defined]
    control.subscribe(control.events.append)  # type: ignore[attr-defined]
    control.start()
    yield control
    control.close()


class StepClock:
    """A clock that moves only when the test says (``clock.now += 5``)."""

    def __init__(self, now: float = 0.0) -> None:
        self.now = now

    def __call__(self) -> float:
        return self.now
