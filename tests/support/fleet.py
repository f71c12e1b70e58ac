"""A fleet on loopback for tests: ROS 2 domains (from the conftest's allocator, so parallel
tests never share one) and ROS 1 masters on free ports, each robot with a node process that
logs what it is told to; everything stopped at the end."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

from console_tui.ros.fleet import Robot
from console_tui.ros.ros_version import ROS1, ROS2

from support.ros1 import SYSTEM_PYTHON, Ros1Master, free_port, ros1_environment
from support.rosproc import NodeProcess

#: What every ROS process of a fleet test has: loopback only, UDP (no shared memory left behind).
ROS2_VALUES = {
    "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
    "FASTDDS_BUILTIN_TRANSPORTS": "UDPv4",
    "RCUTILS_COLORIZED_OUTPUT": "0",
}


@dataclass
class FleetRobot:
    """A robot of the test fleet: what the console is told of it, its node, its master (ROS 1)."""

    robot: Robot
    node: NodeProcess
    master: Ros1Master | None = None

    def log(self, text: str) -> None:
        """The node logs ``text`` at INFO (and has said so)."""
        if self.master is None:
            self.node.send({"cmd": "log", "level": "info", "msg": text})
        else:
            self.node.send({"log": "info", "msg": text})
        self.node.expect_next("logged", 60)


@dataclass
class LoopbackFleet:
    robots: list[FleetRobot] = field(default_factory=list)

    def add_domain(self, name: str, domain: int, node: str) -> FleetRobot:
        env = {**os.environ, **ROS2_VALUES, "ROS_DOMAIN_ID": str(domain)}
        env.pop("ROS_LOCALHOST_ONLY", None)
        process = NodeProcess("talker.py", "--name", node, env=env)
        robot = FleetRobot(Robot(name, ROS2, domain=domain), process)
        self.robots.append(robot)
        process.expect("ready", 60)
        return robot

    def add_master(self, name: str, base: Path, node: str) -> FleetRobot:
        base.mkdir(parents=True, exist_ok=True)
        port = free_port()
        env = ros1_environment(base, port)
        master = Ros1Master(base, port, env)
        master.start(60)
        try:
            process = NodeProcess("rospy_node.py", node, "--period", "0", env=env, python=SYSTEM_PYTHON)
        except BaseException:
            master.stop()
            raise
        robot = FleetRobot(Robot(name, ROS1, master=f"{master.uri}/"), process, master)
        self.robots.append(robot)
        process.expect("ready", 60)
        return robot

    def stop(self) -> None:
        for robot in self.robots:
            robot.node.stop()
            if robot.master is not None:
                robot.master.stop()
