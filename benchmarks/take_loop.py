#!/usr/bin/env python3
"""Take-loop benchmark: what taking one serialized Log message costs, through rclpy and in C.

One process, one node: a publisher fills a raw subscription's reader history with
``--messages`` Log messages (fewer than Fast DDS's default 5,000 kept), then one way of
taking empties it, timed; the ways take turns over ``--rounds`` rounds (medians):

- ``rclpy take + gaps``: ``take_message(Log, raw=True)`` and ``SequenceGaps.see`` a message,
  the intake's loop before the C loop (and still its loop where that cannot be built);
- ``rclpy take``: the take alone;
- ``C take + gaps``: ``compiled_take`` (``take_loop.c``), sequence gaps included;
- ``decode``: ``LogDecoder.decode_columns`` of the messages taken, for scale.

    python benchmarks/take_loop.py [--messages 3000] [--rounds 9] [--domain 93]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).parent))
from _report import ros_environment, ros_header, run_under_header, table


def measure(args: argparse.Namespace) -> dict[str, list[float]]:
    import rclpy
    from rcl_interfaces.msg import Log
    from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
    from rclpy.serialization import serialize_message

    from console_tui.model.formats.ros2_log_msg import LogDecoder
    from console_tui.sources.ros2 import compiled_take
    from console_tui.sources.ros2.loss_counts import LossCounts, SequenceGaps

    compiled, problem = compiled_take.load()
    if compiled is None:
        raise SystemExit(f"the C take loop is not available: {problem}")
    rclpy.init()
    node = rclpy.create_node("take_loop_bench")
    qos = QoSProfile(
        history=HistoryPolicy.KEEP_LAST,
        depth=args.messages,
        reliability=ReliabilityPolicy.RELIABLE,
        durability=DurabilityPolicy.VOLATILE,
    )
    subscription = node.create_subscription(Log, "/take_loop_bench", lambda _m: None, qos, raw=True)
    publisher = node.create_publisher(Log, "/take_loop_bench", qos)
    message = serialize_message(
        Log(name="bench.node", msg="x" * 80, file="/src/some/file.cpp", function="do_it", line=42, level=20)
    )
    handle = subscription.handle

    def rclpy_take(gaps: bool) -> list[bytes]:
        take, see = handle.take_message, SequenceGaps(LossCounts()).see
        taken: list[bytes] = []
        while True:
            got = take(Log, True)
            if got is None:
                return taken
            taken.append(got[0])
            if gaps:
                see(got[1])

    def c_take() -> list[bytes]:
        taken, _lost = compiled(handle.pointer, 1 << 30, {})
        return taken

    ways: dict[str, Callable[[], list[bytes]]] = {
        "rclpy take + gaps": lambda: rclpy_take(True),
        "rclpy take": lambda: rclpy_take(False),
        "C take + gaps": c_take,
    }
    decoder = LogDecoder()
    times: dict[str, list[float]] = {name: [] for name in [*ways, "decode"]}
    time.sleep(1.0)  # the publisher and the subscription match
    for number in range(args.rounds):
        names = list(ways)
        names = names[number % len(names) :] + names[: number % len(names)]
        for name in names:
            for _ in range(args.messages):
                publisher.publish(message)
            time.sleep(0.3)
            started = time.thread_time()
            taken = ways[name]()
            spent = time.thread_time() - started
            if len(taken) != args.messages:
                raise SystemExit(f"{name}: took {len(taken)} of {args.messages}")
            times[name].append(spent / len(taken) * 1e6)
            started = time.thread_time()
            decoder.decode_columns(taken, "/rosout")
            times["decode"].append((time.thread_time() - started) / len(taken) * 1e6)
    node.destroy_node()
    rclpy.shutdown()
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--messages", type=int, default=3000)
    parser.add_argument("--rounds", type=int, default=9)
    parser.add_argument("--domain", type=int, default=int(os.environ.get("CONSOLE_TUI_BENCH_DOMAIN", "93")))
    args = parser.parse_args()
    env = ros_environment(args.domain)
    os.environ.update(env)
    header = ros_header(
        "Take-loop benchmark (benchmarks/take_loop.py)",
        env,
        f"{args.messages:,} messages a round, {args.rounds} rounds; CPU of the taking thread.",
    )
    times: dict[str, Any] = run_under_header(header, lambda: measure(args))
    rows = [
        [name, f"{statistics.median(values):.2f}", f"{min(values):.2f}", f"{max(values):.2f}"]
        for name, values in times.items()
    ]
    print(table(["way", "median µs/msg", "min", "max"], rows))


if __name__ == "__main__":
    main()
