"""The built-in demo: real node processes whose messages the app shows, and that end with it."""

from __future__ import annotations

import subprocess
import sys
import textwrap
import time

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.ui.app import ConsoleApp

from support.rosproc import pid_alive, wait_until
from support.ui import until, until_shown

pytestmark = pytest.mark.ros2


async def test_demo_nodes_log_into_the_app_and_stop_with_it(ros_env):
    from console_tui.demo.launcher import DemoNodes
    from console_tui.sources.live import open_live

    demo = DemoNodes()
    demo.start()
    demo.wait_started()
    queue = IntakeQueue()
    live = open_live(queue, ros=2)
    app = ConsoleApp(queue=queue, sources=[live.source])
    try:
        async with app.run_test(size=(160, 40)) as pilot:
            expected = {
                "count_and_log",
                "navigation.planner",
                "navigation.planner.costmap",  # the planner's child logger, every 2.5 s
                "sensors.lidar_driver",
                "power.battery_monitor",
            }
            await until(pilot, lambda: expected <= {r.node for r in app.main.store}, timeout=30)
            assert {r.node for r in app.main.store} == expected

            # The counter: INFO on 3, WARN on 5, ERROR on 10, FATAL on 20; its DEBUG lines stay
            # in the node, whose logger is at INFO.
            def counter_levels() -> set[int]:
                return {r.level for r in app.main.store if r.node == "count_and_log"}

            await until(pilot, lambda: counter_levels() == {20, 30, 40, 50}, timeout=30, what="a FATAL count")
            fatal = next(r for r in app.main.store if r.node == "count_and_log" and r.level == 50)
            assert fatal.msg.endswith("is divisible by 20") and fatal.source in ("/rosout", "/rosout_agg")
            assert all(r.file.endswith("behaviours.py") and r.line > 0 for r in app.main.store)

            await pilot.press("G")
            shown = await until_shown(pilot, "FOLLOW", f"{fatal.source} 4 pubs", "count_and_log", "is divisible by")
            assert "FOLLOW" in shown and f"{fatal.source} 4 pubs" in shown, shown.splitlines()[-2]
            assert "count_and_log" in shown and "is divisible by" in shown
    finally:
        live.close()
        pids = [p.pid for p in demo.processes]
        demo.stop()
    assert not any(pid_alive(pid) for pid in [*pids, live.source.pid])


def test_demo_nodes_end_when_the_console_dies(ros_env):
    script = textwrap.dedent(
        """
        import time
        from console_tui.demo.launcher import DemoNodes
        demo = DemoNodes(["battery_monitor", "planner"])
        demo.start()
        demo.wait_started()
        print(" ".join(str(p.pid) for p in demo.processes), flush=True)
        time.sleep(60)
        """
    )
    parent = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=ros_env)
    pids = [int(pid) for pid in parent.stdout.readline().split()]
    assert len(pids) == 2 and all(pid_alive(pid) for pid in pids)
    time.sleep(1.0)
    parent.kill()  # no chance to clean up: the children must notice on their own
    parent.wait()
    assert wait_until(lambda: not any(pid_alive(pid) for pid in pids))
