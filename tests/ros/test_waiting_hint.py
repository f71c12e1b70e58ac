"""The empty table says what the console waits for, with real ROS 2: no publisher yet on the
domain, then the first node's messages replace the hint."""

from __future__ import annotations

import asyncio

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.live import open_live
from console_tui.ui.app import ConsoleApp

from support.ui import line_with, screen_text, until

pytestmark = pytest.mark.ros2


async def test_the_empty_table_says_what_it_waits_for_until_the_first_message(nodes, ros_env):
    queue = IntakeQueue()
    live = open_live(queue, topic=None, ros=2)
    app = ConsoleApp(queue=queue, sources=[live.source], utc=True)
    domain = ros_env["ROS_DOMAIN_ID"]
    try:
        async with app.run_test(size=(100, 30)) as pilot:
            waiting = f"waiting for /rosout or /rosout_agg publishers on ROS 2 domain {domain}…"
            await until(pilot, lambda: waiting in screen_text(app), what="the waiting hint")
            y, _ = line_with(app, waiting)
            assert app.main.table.region.y < y < app.main.table.region.bottom, "the hint is in the table"
            talker = nodes.start("talker.py", "--name", "hint_talker")
            await asyncio.to_thread(talker.expect, "ready")
            talker.send({"cmd": "log", "level": "info", "msg": "hello from hint_talker"})
            await until(pilot, lambda: "hello from hint_talker" in screen_text(app), what="the message")
            assert "waiting for" not in screen_text(app)
    finally:
        live.close()
