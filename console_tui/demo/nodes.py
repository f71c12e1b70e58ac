"""Demo nodes, one per process: ``python -m console_tui.demo.nodes NAME``.

Each is a real rclpy node with logger services enabled. It exits when its stdin closes,
so the demo nodes never outlive the console that started them.
"""

from __future__ import annotations

import os
import sys
import threading


def count_and_log(node) -> None:
    """The ROS logging chapter's counter: DEBUG every tick, INFO on 3, WARN on 5, ERROR on 10, FATAL on 20."""
    logger = node.get_logger()
    state = {"count": 0}

    def tick() -> None:
        state["count"] += 1
        count = state["count"]
        logger.debug(f"Counted to {count}")
        if count % 3 == 0:
            logger.info(f"{count} is divisible by 3")
        if count % 5 == 0:
            logger.warning(f"{count} is divisible by 5")
        if count % 10 == 0:
            logger.error(f"{count} is divisible by 10")
        if count % 20 == 0:
            logger.fatal(f"{count} is divisible by 20")

    node.create_timer(0.25, tick)


def planner(node) -> None:
    """A path planner that sometimes fails, with a child logger for its costmap."""
    logger = node.get_logger()
    costmap = logger.get_child("costmap")
    state = {"plan": 0}

    def plan_path() -> None:
        state["plan"] += 1
        plan = state["plan"]
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

    node.create_timer(0.5, plan_path)


def lidar_driver(node) -> None:
    """A sensor driver: a steady stream of scans, dropped packets, multi-line diagnostics."""
    logger = node.get_logger()
    state = {"scan": 0}

    def publish_scan() -> None:
        state["scan"] += 1
        scan = state["scan"]
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

    node.create_timer(0.1, publish_scan)


def battery_monitor(node) -> None:
    """A battery that drains, warns, errors, and is recharged."""
    logger = node.get_logger()
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

    node.create_timer(1.0, check_battery)


#: name -> (node name, namespace, set-up function)
DEMO_NODES = {
    "count_and_log": ("count_and_log", "", count_and_log),
    "planner": ("planner", "/navigation", planner),
    "lidar_driver": ("lidar_driver", "/sensors", lidar_driver),
    "battery_monitor": ("battery_monitor", "/power", battery_monitor),
}


def run(name: str) -> int:
    import rclpy
    from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
    from rclpy.node import Node

    node_name, namespace, set_up = DEMO_NODES[name]
    rclpy.init()
    node = Node(node_name, namespace=namespace, enable_logger_service=True)
    set_up(node)
    executor = SingleThreadedExecutor()
    executor.add_node(node)

    def exit_when_parent_goes() -> None:
        sys.stdin.read()
        rclpy.try_shutdown()

    threading.Thread(target=exit_when_parent_goes, daemon=True).start()
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        executor.shutdown(timeout_sec=0)
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] not in DEMO_NODES:
        print(f"usage: python -m console_tui.demo.nodes {{{','.join(DEMO_NODES)}}}", file=sys.stderr)
        raise SystemExit(2)
    code = run(sys.argv[1])
    # rclpy is shut down by now; the interpreter's own ending (Fast DDS's static
    # destructors) took another 0.5 s or more, and the console waits for its demo nodes.
    sys.stderr.flush()
    os._exit(code)
