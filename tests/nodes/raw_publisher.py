"""A node that publishes serialized Log messages exactly as given, for decoder-path tests.

    raw_publisher.py --topic TOPIC

Prints ``{"event": "ready"}`` once a subscriber has matched. Command ``{"cmd": "publish",
"hex": [H, ...]}`` publishes each hex string's bytes as one message (with /rosout's QoS)
and prints ``{"event": "published", "count": N}``. EOF on stdin ends it.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

import rclpy
from rcl_interfaces.msg import Log
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--topic", required=True)
    args = parser.parse_args()
    rclpy.init()
    node = Node("raw_publisher")
    qos = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    publisher = node.create_publisher(Log, args.topic, qos)
    while publisher.get_subscription_count() < 1:
        time.sleep(0.02)
    print(json.dumps({"event": "ready"}), flush=True)
    for raw in sys.stdin:
        command = json.loads(raw)
        if command.get("cmd") == "publish":
            for text in command["hex"]:
                publisher.publish(bytes.fromhex(text))
            print(json.dumps({"event": "published", "count": len(command["hex"])}), flush=True)
    node.destroy_node()
    rclpy.try_shutdown()


if __name__ == "__main__":
    main()
