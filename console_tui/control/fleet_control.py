"""Logger levels across a fleet: one ``LoggerControl`` per robot, seen as one.

Each robot keeps the control of its ROS (a ROS 2 domain's, with an rclpy context on that
domain; a ROS 1 master's); ``FleetLoggerControl`` lists every robot's nodes, each named
``ROBOT:/node`` (``GraphNode.robot``), and sends each call to the robot the node is on, so the same
node name on two robots is two nodes and a level set on one never reaches the other. Its
events are the robots' events, renamed the same way. A robot whose control has a problem (its
master gone) keeps it to itself: ``problem`` names the robot, and the others go on.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Future
from dataclasses import replace
from typing import Any

from ..model.loggers.logger_levels import GraphNode, TemporaryLevel, robot_qualified, split_robot
from ..ros.fleet import Robot
from ..ros.ros_version import ROS2
from .control_thread import LoggerControl
from .errors import LoggerCallError, NoLoggerServices
from .events import LoggerEvent, NodesChanged, TemporaryEnded
from .futures import failed_future, then
from .graph import GraphWait


def robot_node(robot: str, node: GraphNode) -> GraphNode:
    """``node`` of ``robot``'s graph, named for it (``picker:/talker``)."""
    return replace(node, robot=robot)


def _by_robot(nodes: Iterable[GraphNode]) -> tuple[GraphNode, ...]:
    """Nodes sorted by robot, then as each robot's graph sorts them."""
    return tuple(sorted(nodes, key=lambda node: (node.robot, node.namespace, node.name)))


def split_node(name: str, robots: Iterable[str]) -> tuple[str, str]:
    """``picker:/talker`` -> (``picker``, ``/talker``); a name that names no robot of
    ``robots`` -> ("", name)."""
    robot, node = split_robot(name)
    return (robot, node) if robot in robots else ("", name)


class FleetLoggerControl(LoggerControl):
    """The robots' controls (by robot name) as one; see the module docstring."""

    def __init__(self, controls: Mapping[str, LoggerControl]) -> None:
        first = next(iter(controls.values()))
        super().__init__(call_timeout=first.call_timeout, clock=first.clock)
        self.controls = dict(controls)
        every = list(self.controls.values())
        self.graph_min_s = max(control.graph_min_s for control in every)
        self.graph_quiet_s = max(control.graph_quiet_s for control in every)
        # ROS 1's get_loggers can crash roscpp nodes: a ROS 1 robot's nodes are read when asked
        # (``reads_when_asked``); this is for a node named for no robot.
        self.read_when_asked = any(control.read_when_asked for control in every)
        self.lists_loggers = all(control.lists_loggers for control in every)
        self._fleet_listeners: list[Callable[[LoggerEvent], None]] = []
        self._fleet_lock = threading.Lock()
        for robot, control in self.controls.items():
            control.subscribe(self._forward(robot))

    def reads_when_asked(self, fqn: str) -> bool:
        """A node's levels are read only when asked where its robot's control says so (a ROS 1
        robot's nodes); a ROS 2 robot's are read on highlighting, as with ROS 2 alone."""
        robot, node = split_node(fqn, self.controls)
        control = self.controls.get(robot)
        return control.reads_when_asked(node) if control is not None else self.read_when_asked

    # -- what the robots say, renamed ------------------------------------------------------------

    def _forward(self, robot: str) -> Callable[[LoggerEvent], None]:
        def forward(event: LoggerEvent) -> None:
            fleet_event: LoggerEvent
            if isinstance(event, NodesChanged):
                fleet_event = NodesChanged(self.nodes)
            else:
                fleet_event = TemporaryEnded(self._renamed(robot, event.entry), event.error)
            with self._fleet_lock:
                listeners = list(self._fleet_listeners)
            for listener in listeners:
                listener(fleet_event)

        return forward

    @staticmethod
    def _renamed(robot: str, entry: TemporaryLevel) -> TemporaryLevel:
        return replace(entry, node=robot_qualified(robot, entry.node))

    def subscribe(self, listener: Callable[[LoggerEvent], None]) -> None:
        with self._fleet_lock:
            self._fleet_listeners.append(listener)

    @property  # the base class sets it; here it is the robots'
    def problem(self) -> str:
        return "; ".join(f"{robot}: {control.problem}" for robot, control in self.controls.items() if control.problem)

    @problem.setter
    def problem(self, value: str) -> None:
        pass  # set by the base class's constructor only

    # -- control ---------------------------------------------------------------------------------

    def start(self) -> None:
        for control in self.controls.values():
            control.start()

    def looking(self) -> bool:
        return any(control.looking() for control in self.controls.values())

    def close(self, timeout: float | None = None) -> None:
        """Close every robot's control at once (each restores its temporary levels)."""
        threads = [
            threading.Thread(target=control.close, args=(timeout,), daemon=True) for control in self.controls.values()
        ]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()

    def _robot_of(self, name: str) -> tuple[LoggerControl, str] | None:
        robot, node = split_node(name, self.controls)
        return (self.controls[robot], node) if robot else None

    def no_services(self, node: str) -> NoLoggerServices:
        found = self._robot_of(node)
        return NoLoggerServices(node, found[0].no_services_hint if found else "")

    # -- the graph -------------------------------------------------------------------------------

    @property
    def nodes(self) -> tuple[GraphNode, ...]:
        return _by_robot(robot_node(robot, node) for robot, control in self.controls.items() for node in control.nodes)

    def node(self, fqn: str) -> GraphNode | None:
        robot, name = split_node(fqn, self.controls)
        found = self.controls[robot].node(name) if robot else None
        return None if found is None else robot_node(robot, found)

    def is_settled(self, fqn: str) -> bool:
        found = self._robot_of(fqn)
        return found is not None and found[0].is_settled(found[1])

    def find_node(self, query: str, wait: float) -> list[GraphNode]:
        """``ROBOT:QUERY`` looks on that robot; a query without a robot, on every robot."""
        robot, name = split_node(query, self.controls)
        robots = [robot] if robot else list(self.controls)
        found: list[GraphNode] = []
        for each in robots:
            found += [robot_node(each, node) for node in self.controls[each].find_node(name, wait)]
        return found

    def wait_for_graph(self, deadline: float) -> GraphWait:
        waits = {robot: control.wait_for_graph(deadline) for robot, control in self.controls.items()}
        nodes = _by_robot(robot_node(robot, node) for robot, wait in waits.items() for node in wait.nodes)
        return GraphWait(
            nodes, max(wait.waited_s for wait in waits.values()), all(wait.settled for wait in waits.values())
        )

    # -- calls -----------------------------------------------------------------------------------

    def _call(self, node: str, make: Callable[[LoggerControl, str], Future[Any]]) -> Future[Any]:
        found = self._robot_of(node)
        if found is None:
            robots = ", ".join(self.controls)
            return failed_future(
                LoggerCallError(node, f"{node}: name the robot first, as ROBOT:/node (robots: {robots})")
            )
        return make(*found)

    def get_levels(self, node: str, names: Iterable[str]) -> Future[dict[str, int]]:
        wanted = list(names)
        return self._call(node, lambda control, name: control.get_levels(name, wanted))

    def set_levels(self, node: str, levels: Mapping[str, int]) -> Future[dict[str, int]]:
        return self._call(node, lambda control, name: control.set_levels(name, levels))

    def set_temporary(self, node: str, logger: str, level: int, seconds: float) -> Future[TemporaryLevel]:
        robot, _ = split_node(node, self.controls)
        future = self._call(node, lambda control, name: control.set_temporary(name, logger, level, seconds))
        return then(future, lambda entry: self._renamed(robot, entry)) if robot else future

    def end_temporary(self, node: str, logger: str) -> Future[dict[str, int]]:
        return self._call(node, lambda control, name: control.end_temporary(name, logger))

    def temporaries(self) -> tuple[TemporaryLevel, ...]:
        every = [
            self._renamed(robot, entry) for robot, control in self.controls.items() for entry in control.temporaries()
        ]
        return tuple(sorted(every, key=lambda entry: entry.deadline))

    # -- the base class's ROS parts: a fleet's control makes no calls of its own -------------------

    def _open(self) -> None:
        raise AssertionError("a fleet's logger control makes no calls of its own")

    def _look(self) -> tuple[Iterable[GraphNode], frozenset[str]]:
        raise AssertionError("a fleet's logger control makes no calls of its own")

    def _call_get(self, node: str, names: list[str]) -> Future[dict[str, int]]:
        raise AssertionError("a fleet's logger control makes no calls of its own")

    def _call_set(self, node: str, levels: dict[str, int], *, restore: bool) -> Future[dict[str, int]]:
        raise AssertionError("a fleet's logger control makes no calls of its own")

    def _send(self, call: Any) -> Any:
        raise AssertionError("a fleet's logger control makes no calls of its own")

    def _drop(self, call: Any) -> None:
        raise AssertionError("a fleet's logger control makes no calls of its own")

    def _shutdown(self) -> None:
        raise AssertionError("a fleet's logger control makes no calls of its own")


def open_fleet_loggers(
    robots: Sequence[Robot], cleanups: list[Callable[[], object]], **options: Any
) -> FleetLoggerControl:
    """The logger control of every robot's nodes (``FleetLoggerControl``, not started): for a
    ROS 2 robot an rclpy context of this process on its domain, for a ROS 1 robot its master;
    ``options`` go to each robot's control (``call_timeout``, ``include_hidden``). What to shut
    down after the control is closed goes into ``cleanups``. ``RosUnavailable`` when a ROS 2
    robot's context cannot start."""
    controls: dict[str, LoggerControl] = {}
    for robot in robots:
        if robot.ros == ROS2:
            from ..ros.ros2.runtime import start_ros2
            from .ros2.logger_control import Ros2LoggerControl

            runtime = start_ros2(robot.domain)
            cleanups.append(runtime.shutdown)
            controls[robot.name] = Ros2LoggerControl(runtime, **options)
        else:
            from ..ros.ros1.environment import Ros1Environment
            from .ros1.logger_control import Ros1LoggerControl

            controls[robot.name] = Ros1LoggerControl(Ros1Environment.from_environ(robot.environment()), **options)
    return FleetLoggerControl(controls)
