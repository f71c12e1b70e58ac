"""A ROS 2 node for the tests of ``console-tui run``: logs ``count N`` (INFO, to its console and
/rosout), prints ``printed N`` on stdout, and ends with exit status ``--exit`` (a death when not 0).

    python ros2_counter.py NAME [--count N] [--exit CODE]
"""

from __future__ import annotations

import argparse
import time

import rclpy
from rclpy.node import Node


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("name")
    parser.add_argument("--count", type=int, default=3)
    parser.add_argument("--exit", type=int, default=0)
    args = parser.parse_args()
    rclpy.init()
    node = Node(args.name)
    for number in range(args.count):
        node.get_logger().info(f"count {number}")
        print(f"printed {number}", flush=True)
        time.sleep(0.2)
    time.sleep(4.0)  # a console that joins late gets its /rosout history while it lives
    node.destroy_node()
    rclpy.try_shutdown()
    raise SystemExit(args.exit)


if __name__ == "__main__":
    main()
