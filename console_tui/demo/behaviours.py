"""What the demo nodes log, the same in ROS 1 and ROS 2: a small robot's worth of messages.

Each behaviour gets a ``logger`` (``debug``, ``info``, ``warning``, ``error``, ``fatal`` and
``get_child(name)``, as rclpy's loggers have them) and ``every(seconds, callback)`` to call
``callback`` periodically. ``nodes.py`` runs them on rclpy; ``ros1_nodes.py`` on rospy, with the
system Python (which may be as old as 3.8 on a Noetic machine): keep this module plain.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # only in annotations: Python 3.8 cannot subscript collections.abc.Callable
    from collections.abc import Callable

    Every = Callable[[float, Callable[[], None]], Any]


def every_count(every: Every, seconds: float, callback: Callable[[int], None]) -> None:
    """``callback(1)``, ``callback(2)`` and so on, one every ``seconds``."""
    counter = itertools.count(1)
    every(seconds, lambda: callback(next(counter)))


def count_and_log(logger: Any, every: Every) -> None:
    """The ROS logging chapter's counter: DEBUG every tick, INFO on 3, WARN on 5, ERROR on 10, FATAL on 20."""

    def tick(count: int) -> None:
        logger.debug(f"Counted to {count}")
        if count % 3 == 0:
            logger.info(f"{count} is divisible by 3")
        if count % 5 == 0:
            logger.warning(f"{count} is divisible by 5")
        if count % 10 == 0:
            logger.error(f"{count} is divisible by 10")
        if count % 20 == 0:
            logger.fatal(f"{count} is divisible by 20")

    every_count(every, 0.25, tick)


def planner(logger: Any, every: Every) -> None:
    """A path planner that sometimes fails, with a child logger for its costmap."""
    costmap = logger.get_child("costmap")

    def plan_path(plan: int) -> None:
        goal = (plan % 17 * 0.5, plan % 11 * -0.25)
        if plan % 23 == 0:
            logger.error(f"Timed out waiting for costmap update after 1.2 s (goal {goal[0]:.2f}, {goal[1]:.2f})")
        elif plan % 7 == 0:
            logger.warning("planner failed to find a path within 0.5 s, retrying with relaxed tolerance")
        else:
            logger.info(
                f"Planned path to ({goal[0]:.2f}, {goal[1]:.2f}): {12 + plan % 30} poses, {1.5 + plan % 9 * 0.3:.1f} m"
            )
        if plan % 5 == 0:
            update_costmap(plan)

    def update_costmap(plan: int) -> None:
        costmap.info(f"costmap updated: 0.05 m/cell, {400 + plan % 50} obstacles")
        logger.debug(f"costmap age {plan % 4 * 0.1:.1f} s")

    every_count(every, 0.5, plan_path)


def lidar_driver(logger: Any, every: Every) -> None:
    """A sensor driver: a steady stream of scans, dropped packets, multi-line diagnostics."""

    def publish_scan(scan: int) -> None:
        logger.debug(f"scan {scan}: raw packet batch of 12 packets")
        if scan % 10 == 0:
            logger.info(f"scan {scan}: 720 points, {0.6 + scan % 5 * 0.1:.1f} ms")
        if scan % 37 == 0:
            logger.warning(f"dropped {scan % 4 + 1} packets from 192.0.2.10: checksum mismatch")
        if scan % 100 == 0:
            report_diagnostics(scan)

    def report_diagnostics(scan: int) -> None:
        logger.info(
            f"diagnostics at scan {scan}:\n  temperature: {40 + scan % 7}.2 C\n  motor: 600 rpm\n  firmware: 2.3.1"
        )

    every_count(every, 0.1, publish_scan)


def battery_monitor(logger: Any, every: Every) -> None:
    """A battery that drains, warns, errors, and is recharged."""
    state = {"percent": 84}

    def check_battery() -> None:
        state["percent"] -= 3
        percent = state["percent"]
        volts = 21.0 + percent * 0.05
        if percent <= 0:
            state["percent"] = 100
            logger.info("docked: charging complete, battery at 100%")
        elif percent <= 10:
            logger.error(f"battery critical: {volts:.1f} V, {percent}%: returning to dock")
        elif percent <= 25:
            logger.warning(f"battery low: {volts:.1f} V, {percent}%")
        else:
            logger.info(f"battery {volts:.1f} V, {percent}%")

    every(1.0, check_battery)


#: name -> (node name, namespace, set-up function)
DEMO_NODES = {
    "count_and_log": ("count_and_log", "", count_and_log),
    "planner": ("planner", "/navigation", planner),
    "lidar_driver": ("lidar_driver", "/sensors", lidar_driver),
    "battery_monitor": ("battery_monitor", "/power", battery_monitor),
}
