"""A real rclpy node that republishes /rosout on /rosout_agg, as the classic rosout node does.

Prints {"event": "ready"} once up; ends when stdin closes.
"""

import json
import sys
import threading

import rclpy
from rcl_interfaces.msg import Log
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy


def main() -> None:
    rclpy.init()
    node = Node("rosout_aggregator", enable_rosout=False)
    qos = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    publisher = node.create_publisher(Log, "/rosout_agg", qos)
    node.create_subscription(Log, "/rosout", publisher.publish, qos)
    executor = SingleThreadedExecutor()
    executor.add_node(node)

    def wait_for_eof() -> None:
        sys.stdin.read()
        rclpy.try_shutdown()

    threading.Thread(target=wait_for_eof, daemon=True).start()
    print(json.dumps({"event": "ready"}), flush=True)
    try:
        executor.spin()
    except ExternalShutdownException:
        pass
    finally:
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
