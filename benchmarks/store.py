#!/usr/bin/env python3
"""Store benchmark: memory and time to hold 1,000,000 realistic records, and the cost at the bound.

Records look like a robot's log: 40 nodes, 120 source files, 300 functions, messages of
60-120 characters with numbers in them, mostly INFO. They are made in batches of 1,000
(as the intake hands them over) with node, file and function strings shared between
records, as the CDR decoder shares them; making them is not timed.

    python benchmarks/store.py                    # 1,000,000 records, then 300,000 more at the bound
    python benchmarks/store.py --records 200000   # smaller
    python benchmarks/store.py --list-reference   # also: the same records as a plain list
    python benchmarks/store.py --bare             # without the app's Textual loaded first
    python benchmarks/store.py --app              # also: the app headless over the full store
    python benchmarks/store.py --app --loggers    # ... as it is once the logger levels pane opened

By default the process first loads what the app has loaded when records arrive (Textual),
so the RSS is the app's, not just the store's. With ``--loggers`` also an rclpy context with
a node (on a loopback-only ROS domain of its own), as the app has once its logger levels pane
was opened. With ``--app`` the app itself then runs headless (160x48)
over the full store, and its RSS is measured once its overview (storms, timeline) has counted
every record: what the app process holds for a million records.
"""

from __future__ import annotations

import argparse
import gc
import os
import random
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).parent))
from _report import machine_line, table, verdict

from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord

BATCH = 1_000
TARGET_MB = 150
WORDS = [
    "goal",
    "received",
    "planning",
    "path",
    "costmap",
    "update",
    "laser",
    "scan",
    "dropped",
    "frame",
    "transform",
    "timeout",
    "odom",
    "map",
    "battery",
    "voltage",
    "motor",
    "current",
    "joint",
    "limit",
    "reached",
    "velocity",
    "command",
    "published",
    "subscriber",
    "matched",
    "parameter",
    "changed",
    "retrying",
    "connection",
    "camera",
    "exposure",
    "image",
    "latency",
    "ms",
    "ok",
    "failed",
    "waiting",
    "for",
]


def rss_mb() -> float:
    with open("/proc/self/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


class RecordMaker:
    """Realistic records, batch by batch, reproducibly."""

    def __init__(self, seed: int = 1) -> None:
        rng = self.rng = random.Random(seed)
        self.nodes = [f"robot.{rng.choice(['nav', 'perception', 'hw', 'ui'])}.node_{i}" for i in range(40)]
        self.files = [f"/opt/robot/src/pkg_{i % 17}/src/module_{i}.cpp" for i in range(120)]
        self.functions = [
            f"{rng.choice(['on', 'handle', 'update', 'publish'])}_{rng.choice(WORDS)}_{i}" for i in range(300)
        ]
        self.levels = [10] * 5 + [20] * 80 + [30] * 10 + [40] * 4 + [50]
        self.phrases = [" ".join(rng.choice(WORDS) for _ in range(20)) for _ in range(1024)]
        self.stamp = 1_700_000_000_000_000_000
        self.number = 0

    def batch(self, size: int = BATCH) -> list[LogRecord]:
        """Records with unique message texts (each its own ``str``, as decoded messages are)."""
        choice = self.rng.choice
        nodes, files, functions, levels, phrases = self.nodes, self.files, self.functions, self.levels, self.phrases
        out = []
        for _ in range(size):
            self.number += 1
            self.stamp += 10_000 + (self.number * 7919) % 2_000_000
            text = f"{self.number}: {choice(phrases)}"[: 60 + self.number % 61]
            out.append(
                LogRecord(
                    self.stamp,
                    choice(levels),
                    choice(nodes),
                    text,
                    choice(files),
                    choice(functions),
                    1 + self.number % 3000,
                    "/rosout",
                )
            )
        return out


def fill(store: LogStore, maker: RecordMaker, count: int) -> float:
    """Seconds spent in ``store.extend`` adding ``count`` records."""
    spent = 0.0
    for _ in range(count // BATCH):
        batch = maker.batch()
        began = time.perf_counter()
        store.extend_records(batch)
        spent += time.perf_counter() - began
    return spent


def list_reference(records: int) -> float:
    """RSS growth (MB) of the same records kept as a plain list of ``LogRecord`` objects."""
    maker = RecordMaker()
    before = rss_mb()
    kept: list[LogRecord] = []
    for _ in range(records // BATCH):
        kept.extend(maker.batch())
    gc.collect()
    return rss_mb() - before


def app_rss_mb(store: LogStore) -> float:
    """The process's RSS with the app running headless over ``store``, its overview counted."""
    import asyncio

    from console_tui.ui.app import ConsoleApp

    async def run() -> float:
        app = ConsoleApp(store=store)
        async with app.run_test(size=(160, 48)) as pilot:
            await pilot.pause(0.5)
            while app.main.storms.behind or app.main.timeline.behind:
                await asyncio.sleep(0.05)
            gc.collect()
            return rss_mb()

    return asyncio.run(run())


def load_the_apps_libraries(loggers: bool) -> tuple[str, Any]:
    """Import Textual and, with ``loggers``, start an rclpy context with a node, as the app
    does when its logger levels pane first opens.

    Returns what was loaded, and the ROS runtime (or ``None``) to shut down at the end.
    """
    import textual.app
    import textual.widgets  # noqa: F401

    loaded, runtime = "Textual", None
    if not loggers:
        return loaded, runtime
    os.environ.update(ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST", ROS_DOMAIN_ID=str(150 + os.getpid() % 80))
    try:
        from console_tui.ros.ros2.runtime import RosRuntime

        runtime = RosRuntime()
        runtime.create_node("store_benchmark")
        loaded += ", rclpy context and node"
    except Exception:  # no rclpy here: Textual alone
        pass
    return loaded, runtime


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", type=int, default=1_000_000)
    parser.add_argument("--beyond", type=int, default=300_000, help="records added with the store full")
    parser.add_argument("--list-reference", action="store_true", help="also measure a plain list of records")
    parser.add_argument("--bare", action="store_true", help="measure the store alone (Python and the model only)")
    parser.add_argument("--loggers", action="store_true", help="with rclpy and a node, as after the logger pane opened")
    parser.add_argument("--app", action="store_true", help="also run the app headless over the full store")
    parser.add_argument("--reference-only", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.reference_only:
        print(f"{list_reference(args.reference_only):.1f}")
        return

    loaded, runtime = ("the model only", None) if args.bare else load_the_apps_libraries(args.loggers)
    gc.collect()
    baseline = rss_mb()
    store = LogStore(max_messages=args.records)
    maker = RecordMaker()
    fill_seconds = fill(store, maker, args.records)
    gc.collect()
    full_rss = rss_mb()
    beyond_seconds = fill(store, maker, args.beyond)
    gc.collect()
    after_rss = rss_mb()
    assert len(store) == args.records and store.evicted == args.beyond

    began = time.perf_counter()
    for seq in range(store.first_seq, store.end_seq, 997):
        store.get(seq)
    get_us = (time.perf_counter() - began) / len(range(store.first_seq, store.end_seq, 997)) * 1e6

    per_record = (full_rss - baseline) * 1024 * 1024 / args.records
    rows = [
        ["process RSS before any record", f"{baseline:.0f} MB", f"Python with {loaded}"],
        [
            f"process RSS holding {args.records:,} records",
            f"{full_rss:.0f} MB",
            f"<= {TARGET_MB} MB: " + verdict(full_rss <= TARGET_MB, f"over by {full_rss - TARGET_MB:.0f} MB"),
        ],
        ["store's share", f"{full_rss - baseline:.0f} MB ({per_record:.0f} bytes/record)", ""],
        [f"RSS after {args.beyond:,} more at the bound", f"{after_rss:.0f} MB", "steady: the bound holds memory"],
        [
            f"time to add {args.records:,} (batches of {BATCH:,})",
            f"{fill_seconds:.2f} s",
            f"{args.records / fill_seconds:,.0f} records/s",
        ],
        [
            f"time to add {args.beyond:,} with the store full",
            f"{beyond_seconds:.2f} s",
            f"{args.beyond / beyond_seconds:,.0f} records/s (eviction included)",
        ],
        [
            "per record: filling / at the bound",
            f"{fill_seconds / args.records * 1e6:.2f} us / {beyond_seconds / args.beyond * 1e6:.2f} us",
            "the difference is eviction's cost",
        ],
        ["get(seq) of a stored record", f"{get_us:.2f} us", ""],
    ]
    if args.app:
        rows.append(["process RSS with the app running over them", f"{app_rss_mb(store):.0f} MB", "the app's own"])
    if args.list_reference:
        reference = subprocess.run(
            [sys.executable, __file__, "--reference-only", str(args.records)],
            capture_output=True,
            text=True,
            check=True,
        )
        rows.append(
            [f"reference: {args.records:,} LogRecord objects in a list", f"{float(reference.stdout):.0f} MB", ""]
        )
    print("## Store benchmark (benchmarks/store.py)\n")
    print(machine_line())
    print()
    print(table(["measure", "value", "target / note"], rows))
    if runtime is not None:
        runtime.shutdown()


if __name__ == "__main__":
    main()
