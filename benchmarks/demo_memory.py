#!/usr/bin/env python3
"""Demo memory benchmark: what ``console-tui --demo`` holds after minutes of running.

    .venv/bin/python benchmarks/demo_memory.py [--minutes 10] [--every 60] [--loggers]

Runs the app as ``console-tui --demo`` puts it together (the intake process, the logger
levels' control, the demo nodes in processes of their own), headless at 160x48, on a
loopback-only ROS domain of its own, and prints the memory of the app's process and of its
intake process as time goes by: RSS, and PSS (shared library pages split between the
processes that map them, so the two add up honestly). The demo nodes are not counted.
With ``--loggers`` the logger levels pane is opened at the start, so that the app holds rclpy
and a DDS participant of its own, as once a person has opened it.
Target: at most 120 MB after 10 minutes (issue 35).
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _probe import process_pss_mb as pss_mb
from _probe import process_rss_mb
from _report import machine_line, table, verdict

TARGET_MB = 120.0


async def run(minutes: float, every: float, loggers: bool) -> list[list[object]]:
    from console_tui.control.ros2.logger_control import Ros2LoggerControl
    from console_tui.demo.launcher import DEMO_ENVIRONMENT, DemoNodes
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.sources.live import open_live
    from console_tui.ui.app import ConsoleApp

    os.environ.update(DEMO_ENVIRONMENT)
    queue = IntakeQueue()
    live = open_live(queue, ros=2)
    control = Ros2LoggerControl(live.runtime)
    app = ConsoleApp(queue=queue, sources=[live.source, DemoNodes()], logger_control=control)
    rows: list[list[object]] = []
    try:
        async with app.run_test(size=(160, 48)) as pilot:
            if loggers:
                await pilot.press("l")
            began = time.monotonic()
            moments = [every * n for n in range(1, int(minutes * 60 / every) + 1)]
            if not moments or moments[-1] < minutes * 60:
                moments.append(minutes * 60)
            for moment in moments:
                await asyncio.sleep(max(began + moment - time.monotonic(), 0))
                me, intake = os.getpid(), live.source.pid
                row = [
                    f"{(time.monotonic() - began) / 60:.1f}",
                    f"{len(app.main.store):,}",
                    f"{process_rss_mb(me):.0f}",
                    f"{process_rss_mb(intake):.0f}",
                    f"{pss_mb(me):.0f}",
                    f"{pss_mb(intake):.0f}",
                    f"{pss_mb(me) + pss_mb(intake):.0f}",
                    f"{len(gc.get_objects()):,}",
                ]
                rows.append(row)
                print(" ".join(map(str, row)), file=sys.stderr, flush=True)
    finally:
        control.close()
        live.close()
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0)
    parser.add_argument("--every", type=float, default=60.0, help="seconds between measurements (default 60)")
    parser.add_argument("--domain", type=int, default=150 + os.getpid() % 80)
    parser.add_argument("--loggers", action="store_true", help="open the logger levels pane at the start")
    args = parser.parse_args()
    os.environ.update(ROS_DOMAIN_ID=str(args.domain), ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST")
    rows = asyncio.run(run(args.minutes, args.every, args.loggers))
    print("## Demo memory (benchmarks/demo_memory.py)\n")
    print(machine_line() + "\n")
    headers = ["minutes", "messages", "RSS MB app", "RSS MB intake", "PSS MB app", "PSS MB intake"]
    print(table([*headers, "PSS MB both", "tracked objects"], rows))
    last = rows[-1]
    app_rss, both_pss = float(last[2]), float(last[6])
    print(
        f"\nTarget: at most {TARGET_MB:.0f} MB after {args.minutes:g} minutes: the app's RSS {app_rss:.0f} MB, "
        + verdict(app_rss <= TARGET_MB, f"over by {app_rss - TARGET_MB:.0f} MB")
        + f"; the app and its intake process together (PSS) {both_pss:.0f} MB, "
        + verdict(both_pss <= TARGET_MB, f"over by {both_pss - TARGET_MB:.0f} MB")
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
