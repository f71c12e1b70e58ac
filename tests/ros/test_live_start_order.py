"""ROS 2 live start in time order: two real nodes log before the console starts, their
/rosout histories (TRANSIENT_LOCAL) reach it one publisher at a time, and the table's first
rows read in the order the messages were logged, not grouped by node."""

from __future__ import annotations

import asyncio
import time

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.live import LiveIntake, open_live
from console_tui.ui.app import ConsoleApp

from support.ui import table_rows, until

pytestmark = pytest.mark.ros2

#: Apart by more than a late batch must be (``late_records.LATE_NS``): the gap is in the
#: messages' stamps, whatever the machine's speed.
GAP_S = 0.5


def live_app() -> tuple[ConsoleApp, LiveIntake]:
    """The app with the live stream as ``console-tui`` has it: taken in the intake process."""
    queue = IntakeQueue()
    live = open_live(queue, ros=2)
    return ConsoleApp(queue=queue, sources=[live.source], utc=True), live


async def logged_after_gap(node, tag: str) -> list[dict]:
    """``node`` logs one message at each severity once ``GAP_S`` has passed since its call."""
    until_s = time.time() + GAP_S
    while time.time() < until_s:
        await asyncio.sleep(0.05)
    node.send({"cmd": "log_all", "tag": tag})
    return (await asyncio.to_thread(node.expect_next, "logged"))["messages"]


async def test_histories_of_two_nodes_come_in_time_order(nodes):
    first = nodes.start("talker.py", "--name", "first_node", "--debug")
    second = nodes.start("talker.py", "--name", "second_node", "--debug")
    await asyncio.to_thread(first.expect, "ready")
    await asyncio.to_thread(second.expect, "ready")
    logged = []
    for node, tag in ((first, "one"), (second, "two"), (first, "three"), (second, "four")):
        logged += [message["msg"] for message in await logged_after_gap(node, tag)]
    newest = {logged[-6], logged[-1]}  # each node's last message: the last to leave its history

    app, live = live_app()
    try:
        async with app.run_test(size=(160, 40)) as pilot:
            # A history keeps 10 s: on a slow start the oldest may have gone; the newest come.
            await until(pilot, lambda: newest <= {r.msg for r in app.main.store}, what="both nodes' histories")
            received = [msg for msg in logged if msg in {r.msg for r in app.main.store}]
            await until(pilot, lambda: len(table_rows(app)) >= len(received), what="the rows on the screen")
            rows = [line for _, line in sorted(table_rows(app).values())]
            order = [next((msg for msg in logged if msg in line), None) for line in rows]
            assert [msg for msg in order if msg is not None] == received, "\n".join(rows)
            stamps = [record.stamp_ns for record in app.main.store]
            assert stamps == sorted(stamps)
    finally:
        live.close()
