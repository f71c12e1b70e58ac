"""Make the README's screenshots from the real app, headless, on the real demo nodes.

    .venv/bin/python scripts/screenshots.py [--out screenshots] [--seconds 8]

Starts the demo nodes (real rclpy processes, loopback only, a domain of their own), runs
console-tui headless against them, and saves SVG screenshots of its screens.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import sys
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


class Frozen:
    """A source that only shows a status (another app's as it was, or a fleet's robot): no ROS needed."""

    def __init__(self, status) -> None:
        self.status = status

    def start(self) -> None:
        pass

    def stop(self) -> None:
        pass


async def capture(out: Path, seconds: float) -> list[Path]:
    from console_tui.control.ros2.logger_control import Ros2LoggerControl
    from console_tui.demo.launcher import DemoNodes
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.ros.ros2.runtime import RosRuntime
    from console_tui.sources.ros2.live_source import LiveLogSource
    from console_tui.ui.app import ConsoleApp

    demo = DemoNodes(domain=int(os.environ["ROS_DOMAIN_ID"]))  # as --demo shows it
    demo.start()
    runtime = RosRuntime()
    queue = IntakeQueue()
    control = Ros2LoggerControl(runtime)
    live = LiveLogSource(runtime, queue)
    app = ConsoleApp(queue=queue, sources=[live], logger_control=control)
    saved: list[Path] = []

    async def shot(pilot, name: str) -> None:
        await pilot.pause(0.3)
        path = out / f"{name}.svg"
        pilot.app.save_screenshot(filename=path.name, path=str(path.parent))
        saved.append(path)

    try:
        async with app.run_test(size=(160, 42)) as pilot:
            await pilot.pause(seconds)
            await shot(pilot, "live-table")
            await pilot.press("up", "up", "up", "up", "enter")
            await shot(pilot, "detail")
            await pilot.press("escape", "question_mark")
            await shot(pilot, "help")
            await pilot.press("escape", "end", "l")  # the app joins the graph: wait for the nodes
            for _ in range(300):
                if len(pilot.app.main.logger_pane.nodes) >= 4:
                    break
                await pilot.pause(0.1)
            await pilot.press("down")  # the logger levels of the second node
            await pilot.pause(1.0)
            await pilot.press("right", "t", "enter")  # DEBUG for 30 s
            await pilot.pause(3.0)
            await shot(pilot, "logger-pane")
            await pilot.press("escape", "l", "slash")
            pilot.app.main.query_bar.input.value = '-node:sensors.* +level>=warn +"failed"'
            await shot(pilot, "query-line")
            await pilot.press("enter", "r")
            await pilot.pause(1.0)
            await shot(pilot, "rules-pane")
            await pilot.press("escape", "r")
            await pilot.press("ctrl+n")  # the node panel: counts per severity and rates
            await pilot.pause(1.0)
            await shot(pilot, "node-panel")
            await pilot.press("escape", "ctrl+n", "end", "f")
            pilot.app.main.search_bar.input.value = "failed"
            await pilot.pause(0.5)
            await pilot.press("enter", "N", "N")  # two matches up: the marks around it
            await shot(pilot, "search")
            await pilot.press("escape", "home", "t", "t", "t")  # the time since the first message
            await shot(pilot, "time-since-first")
        # Narrow terminals: the status line by priority, the node panel, the summary, the help,
        # over the same messages and the sources as they were (their status, frozen).
        origin = f"ROS 2 domain {os.environ['ROS_DOMAIN_ID']}"  # as the intake process says it
        frozen = [Frozen(replace(live.status, origin=origin)), Frozen(demo.status)]
        for width, height in ((80, 24), (100, 30)):
            narrow = ConsoleApp(store=app.main.store, sources=frozen)
            size = f"{width}x{height}"
            async with narrow.run_test(size=(width, height)) as pilot:
                await pilot.pause(1.0)
                await shot(pilot, f"live-table-{size}")
                await pilot.press("ctrl+n")
                await shot(pilot, f"node-panel-{size}")
                await pilot.press("escape", "ctrl+n", "S")
                await shot(pilot, f"summary-{size}")
                await pilot.press("escape", "question_mark")
                await shot(pilot, f"help-{size}")
    finally:
        control.close()
        runtime.shutdown()
        demo.stop()
    return saved


async def capture_folder(out: Path) -> list[Path]:
    """A ROS 1 run folder (the test fixture) opened whole: every log merged, the file a column.
    Needs no ROS: times are shown in UTC, the folder's plain-output file dated as in the run."""
    import shutil
    import tempfile
    import time

    from console_tui.ui.app import ConsoleApp

    os.environ["TZ"] = "UTC"  # the run's Python logs give local times: read them as the run wrote them
    time.tzset()
    with tempfile.TemporaryDirectory() as scratch:
        run = Path(scratch) / "c0ffee00-d4b2-11eb-9c3e-0242ac110002"
        shutil.copytree(ROOT / "tests" / "data" / "ros_log" / run.name, run)
        os.utime(run / "rosout-1-stdout.log", ns=(1624512195_200_000_000,) * 2)
        app = ConsoleApp(files=[str(run)], utc=True)
        async with app.run_test(size=(160, 30)) as pilot:
            while app.main.files.loading or len(app.main.store) < 20:
                await pilot.pause(0.1)
            await pilot.press("home")
            await pilot.pause(0.5)
            path = out / "merged-folder.svg"
            app.save_screenshot(filename=path.name, path=str(path.parent))
    return [path]


def overview_records() -> list:
    """Ten minutes of a robot's log (no ROS): five nodes at their own rates, a WARN now and
    then, an ERROR burst at 6 min (the motor driver times out), and in the last half minute
    tf_listener repeating one warning 3,000 times. Fixed, so the shots are the same each time."""
    import random

    from console_tui.model.store.record import LogRecord

    second = 1_000_000_000
    start = 1_795_000_000 * second  # 11:06:40 UTC
    rng = random.Random(16)
    made: list[LogRecord] = []
    every = {  # node: (messages a second, what it says)
        "navigation.planner": (
            4,
            lambda i: f"Planned path to ({i % 40 / 4:.2f}, {-(i % 17) / 4:.2f}): {i % 90 + 10} poses",
        ),
        "sensors.lidar_driver": (10, lambda i: f"scan {i}: 720 points, {0.4 + (i % 7) / 10:.1f} ms"),
        "power.battery_monitor": (1, lambda i: f"battery {25.2 - i / 600:.1f} V, {90 - i // 20}%"),
        "control.base_controller": (20, lambda i: f"cmd_vel {i % 50 / 100:.2f} m/s, wheels ok"),
    }
    for node, (rate, text) in every.items():
        for i in range(600 * rate):
            stamp = start + i * second // rate + rng.randrange(second // rate // 2)
            level = 30 if rng.random() < 0.0004 else 20
            message = text(i) if level == 20 else f"{node.rpartition('.')[2]}: late by {rng.randint(5, 90)} ms"
            name = node.rpartition(".")[2]
            made.append(LogRecord(stamp, level, node, message, file=f"{name}.cpp", function="spin_once", line=120))
    for i in range(40):  # the burst: the motor driver stops answering for 2 s
        stamp = start + 360 * second + i * second // 20
        made.append(
            LogRecord(
                stamp,
                40,
                "control.base_controller",
                f"motor driver timeout on /dev/ttyACM0 (try {i + 1})",
                file="base_controller.cpp",
                function="write_command",
                line=311,
            )
        )
    made.append(
        LogRecord(
            start + 362 * second,
            30,
            "control.base_controller",
            "motor driver back after 2.0 s",
            file="base_controller.cpp",
            function="write_command",
            line=318,
        )
    )
    for i in range(3000):  # the storm: one warning, a hundred a second
        stamp = start + 572 * second + i * second // 100  # from a column's start (4 s columns at 160)
        made.append(
            LogRecord(
                stamp,
                30,
                "tf_listener",
                "Lookup would require extrapolation into the future. Requested time 1795000572.000 but the latest data is at 1795000571.950",
                file="buffer_core.cpp",
                function="lookupTransform",
                line=226,
            )
        )
    made.sort(key=lambda record: record.stamp_ns)
    return made


async def capture_overview(out: Path) -> list[Path]:
    """The overview on ``overview_records``: the timeline with its ERROR burst and the storm
    collapsed, a jump from the burst's column, the summary. No ROS."""
    from console_tui.model.store.log_store import LogStore
    from console_tui.ui.app import ConsoleApp

    store = LogStore()
    store.extend_records(overview_records())
    app = ConsoleApp(store=store, utc=True)
    saved: list[Path] = []

    async def shot(pilot, name: str) -> None:
        await pilot.pause(0.5)
        path = out / f"{name}.svg"
        app.save_screenshot(filename=path.name, path=str(path.parent))
        saved.append(path)

    async with app.run_test(size=(160, 36)) as pilot:
        while app.main.storms.behind or app.main.timeline.behind or not app.main.storms.storm_count:
            await pilot.pause(0.1)
        # A click on the column where the rate jumps: the table there, the storm one row.
        columns = app.main.timeline.columns(app.main.timeline_strip.size.width)
        storm = next(column for column, counts in enumerate(columns.counts) if counts[2] > 100)
        await pilot.click("#timeline", offset=(storm, 2))
        await shot(pilot, "overview")
        await pilot.press("escape", "T", "home")  # back to the table, then a column picked by key
        strip = app.main.timeline_strip
        columns = app.main.timeline.columns(strip.size.width)
        burst = next(column for column, counts in enumerate(columns.counts) if counts[3])
        await pilot.press(*["right"] * burst)
        await pilot.press("enter")  # the strip keeps the focus: the picked column shows
        await shot(pilot, "overview-jump")
        await pilot.press("escape", "end", "S")
        await shot(pilot, "summary")
    return saved


def fleet_records() -> list:
    """Ten seconds of a small fleet (no ROS): two ROS 2 robots and a ROS 1 forklift, each
    with a node called talker, the picker handing a tote over to the cart."""
    import time

    from console_tui.model.store.record import LogRecord

    second = 1_000_000_000
    start = (time.time_ns() // (60 * second) - 1) * 60 * second  # live stamps: the minute before this one
    script = [
        (0.0, "picker", 20, "/arm/planner", "Picked tote 1042 from shelf B3"),
        (0.4, "cart", 20, "talker", "Docking at hand-over station 2"),
        (1.1, "forklift", 20, "/talker", "Pallet 88 lowered at dock 4"),
        (1.8, "picker", 20, "talker", "Moving to hand-over station 2"),
        (2.5, "cart", 30, "talker", "Dock alignment off by 4 cm, correcting"),
        (3.2, "forklift", 20, "/lift_controller", "Forks at 0.00 m"),
        (3.9, "picker", 20, "talker", "At hand-over station 2, waiting for the cart"),
        (4.3, "cart", 20, "talker", "Docked at hand-over station 2"),
        (5.0, "picker", 20, "/arm/planner", "Placing tote 1042 on the cart"),
        (5.6, "cart", 40, "/conveyor", "Tote sensor timeout: no tote seen in 2.0 s"),
        (5.7, "picker", 20, "/arm/planner", "Tote 1042 released"),
        (6.3, "cart", 30, "talker", "Hand-over not confirmed, holding at station 2"),
        (6.9, "forklift", 30, "/talker", "Battery 21%: returning to charge after this job"),
        (7.5, "picker", 40, "talker", "Hand-over of tote 1042 unconfirmed by cart"),
        (8.1, "cart", 20, "/conveyor", "Tote sensor recalibrated"),
        (8.6, "cart", 20, "talker", "Tote 1042 on board, leaving station 2"),
        (9.2, "picker", 20, "talker", "Hand-over of tote 1042 confirmed"),
    ]
    return [
        LogRecord(start + int(at * second), level, node, msg, file="handover.py", function="step", line=42, robot=robot)
        for at, robot, level, node, msg in script
    ]


async def capture_fleet(out: Path) -> list[Path]:
    """A fleet in one console (no ROS): the Robot column in each robot's colour, the robots'
    states on the status line."""
    from console_tui.model.store.log_store import LogStore
    from console_tui.model.store.record_batch import RecordColumns
    from console_tui.ros.fleet import Robot
    from console_tui.ros.ros_version import ROS1, ROS2
    from console_tui.sources.status import SourceStatus
    from console_tui.ui.app import ConsoleApp

    robots = [
        Robot("picker", ROS2, domain=3, colour="cyan"),
        Robot("cart", ROS2, domain=4, colour="magenta"),
        Robot("forklift", ROS1, master="http://10.0.0.7:11311/", colour="yellow"),
    ]
    sources = [
        Frozen(SourceStatus(topic="/rosout", publishers=3, running=True, robot="picker", path="c+cdr")),
        Frozen(SourceStatus(topic="/rosout", publishers=2, running=True, robot="cart", path="c+cdr")),
        Frozen(SourceStatus(topic="/rosout_agg", publishers=1, running=True, robot="forklift", path="tcpros")),
    ]
    store = LogStore()
    store.extend(RecordColumns.from_records(fleet_records()))
    app = ConsoleApp(store=store, sources=sources, utc=True, robots=robots)
    for column in ("file", "function", "line"):
        app.main.table.set_column_shown(column, False)
    async with app.run_test(size=(120, 26)) as pilot:
        await pilot.pause(0.5)
        await pilot.press("end")
        await pilot.pause(0.5)
        path = out / "fleet.svg"
        app.save_screenshot(filename=path.name, path=str(path.parent))
    return [path]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "screenshots")
    parser.add_argument("--seconds", type=float, default=8.0, help="how long the demo runs before the first shot")
    parser.add_argument(
        "--no-ros",
        action="store_true",
        help="only the shots that need no ROS (the run folder, the overview, the fleet)",
    )
    args = parser.parse_args()
    os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    os.environ.setdefault("ROS_DOMAIN_ID", "87")
    args.out.mkdir(parents=True, exist_ok=True)
    saved = [] if args.no_ros else asyncio.run(capture(args.out, args.seconds))
    saved += asyncio.run(capture_folder(args.out))
    saved += asyncio.run(capture_overview(args.out))
    saved += asyncio.run(capture_fleet(args.out))
    for path in saved:
        print(path.relative_to(ROOT) if path.is_relative_to(ROOT) else path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
