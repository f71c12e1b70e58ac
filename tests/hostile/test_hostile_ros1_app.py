"""The app against a hostile ROS 1 master (issue 33, item 3, the figure): a valid 600 MB
``getSystemState`` answer. The app stays alive and answers keys, the good publisher's rows
show, its memory stays bounded, and the logger control asks the master for nodes only while
the logger pane is open."""

from __future__ import annotations

from console_tui.control.ros1.logger_control import Ros1LoggerControl
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.ros.ros1.environment import Ros1Environment
from console_tui.sources.live import open_live
from console_tui.ui.app import ConsoleApp

from support.hostile_ros1 import FakeMaster, FakePublisher, huge_system_state, reset_rss_peak, rss_peak_mb
from support.ui import screen_text, until


async def test_the_app_against_a_600_mb_system_state(monkeypatch):
    with FakePublisher() as good, FakeMaster([good.uri], getSystemState=huge_system_state(600 << 20)) as master:
        monkeypatch.setenv("ROS_MASTER_URI", master.uri)
        monkeypatch.setenv("ROS_IP", "127.0.0.1")
        environment = Ros1Environment(master.uri, "127.0.0.1", "127.0.0.1")
        queue = IntakeQueue()
        control = Ros1LoggerControl(environment, call_timeout=30.0)
        live = open_live(queue, ros=1)  # the intake in a process of its own, as the app runs it
        source = live.source
        app = ConsoleApp(queue=queue, sources=[source], utc=True, logger_control=control)
        reset_rss_peak()
        before = rss_peak_mb()
        try:
            async with app.run_test(size=(120, 30)) as pilot:
                await until(pilot, lambda: "good 5" in screen_text(app), 120, "the good publisher's rows")
                await until(pilot, lambda: master.calls["getSystemState"] >= 2, 120, "the intake asking twice")
                assert master.callers[("getSystemState", control.caller_id)] == 0  # the pane is closed
                await pilot.press("space")
                await until(pilot, lambda: "PAUSED" in screen_text(app).splitlines()[-2], what="the keys answered")
                await pilot.press("l")
                await until(pilot, lambda: master.callers[("getSystemState", control.caller_id)] >= 1, 120, "a look")
                await until(pilot, lambda: "refused" in screen_text(app) or "no answer" in screen_text(app), 120)
                await pilot.press("l", "space")
                await until(pilot, lambda: "PAUSED" not in screen_text(app).splitlines()[-2], what="resumed")
                assert source.status.running
        finally:
            control.close()
            live.close()
        grown = rss_peak_mb() - before
        assert grown < 300, f"peak RSS grew by {grown:.0f} MB"
