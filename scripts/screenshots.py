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
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


async def capture(out: Path, seconds: float) -> list[Path]:
    from console_tui.demo.launcher import DemoNodes
    from console_tui.model.intake_queue import IntakeQueue
    from console_tui.sources.ros2.live_source import LiveLogSource
    from console_tui.sources.ros2.logger_control import Ros2LoggerControl
    from console_tui.sources.ros2.runtime import RosRuntime
    from console_tui.ui.app import ConsoleApp

    demo = DemoNodes()
    demo.start()
    runtime = RosRuntime()
    queue = IntakeQueue()
    control = Ros2LoggerControl(runtime)
    app = ConsoleApp(queue=queue, sources=[LiveLogSource(runtime, queue)], logger_control=control)
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
            await pilot.press("escape", "end", "l", "down")  # the logger levels of the second node
            await pilot.pause(1.0)
            await pilot.press("right", "t", "enter")  # DEBUG for 30 s
            await pilot.pause(3.0)
            await shot(pilot, "logger-pane")
            await pilot.press("escape", "l", "slash")
            pilot.app.query_bar.input.value = '-node:sensors.* +level>=warn +"failed"'
            await shot(pilot, "query-line")
            await pilot.press("enter", "r")
            await pilot.pause(1.0)
            await shot(pilot, "rules-pane")
            await pilot.press("escape", "r")
            await pilot.press("ctrl+n")  # the node panel: counts per severity and rates
            await pilot.pause(1.0)
            await shot(pilot, "node-panel")
            await pilot.press("escape", "ctrl+n", "end", "f")
            pilot.app.search_bar.input.value = "failed"
            await pilot.pause(0.5)
            await pilot.press("enter", "N", "N")  # two matches up: the marks around it
            await shot(pilot, "search")
            await pilot.press("escape", "home", "t", "t", "t")  # the time since the first message
            await shot(pilot, "time-since-first")
        narrow = ConsoleApp(store=app.store)
        async with narrow.run_test(size=(80, 24)) as pilot:
            await pilot.pause(1.0)
            await shot(pilot, "live-table-80x24")
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
            while app.loading or len(app.store) < 22:
                await pilot.pause(0.1)
            await pilot.press("home")
            await pilot.pause(0.5)
            path = out / "merged-folder.svg"
            app.save_screenshot(filename=path.name, path=str(path.parent))
    return [path]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "screenshots")
    parser.add_argument("--seconds", type=float, default=8.0, help="how long the demo runs before the first shot")
    parser.add_argument("--folder-only", action="store_true", help="only the merged run folder (no ROS needed)")
    args = parser.parse_args()
    os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    os.environ.setdefault("ROS_DOMAIN_ID", "87")
    args.out.mkdir(parents=True, exist_ok=True)
    saved = [] if args.folder_only else asyncio.run(capture(args.out, args.seconds))
    saved += asyncio.run(capture_folder(args.out))
    for path in saved:
        print(path.relative_to(ROOT) if path.is_relative_to(ROOT) else path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
