"""End to end with real ROS 2: node processes log, the headless app shows every field."""

from __future__ import annotations

import asyncio
import contextlib
import subprocess
import sys
import time

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.live import LiveIntake, open_live
from console_tui.ui.app import ConsoleApp

from support.rosproc import PATIENCE_S
from support.ui import line_with, screen_text, until, until_shown, widget_lines

pytestmark = pytest.mark.ros2

#: How long messages to a subscription not matched yet are awaited before more are sent (those
#: logged before the match are lost): the pace of the tries, not a deadline (``PATIENCE_S``).
RESEND_S = 1.0


def live_app(topic: str | None = None) -> tuple[ConsoleApp, LiveIntake]:
    """The app with the live stream as ``console-tui`` has it: taken in the intake process."""
    queue = IntakeQueue()
    live = open_live(queue, topic=topic, ros=2)
    return ConsoleApp(queue=queue, sources=[live.source], utc=True), live


def fields(record) -> dict:
    return {
        "level": record.level,
        "msg": record.msg,
        "file": record.file,
        "function": record.function,
        "line": record.line,
    }


def records_of(app: ConsoleApp, node: str) -> list:
    return [record for record in app.main.store if record.node == node]


async def test_every_severity_with_every_field_in_order_late_join_and_volatile(nodes):
    early = nodes.start("talker.py", "--name", "early", "--namespace", "/e2e", "--debug")
    await asyncio.to_thread(early.expect, "ready")
    early.send({"cmd": "log_all", "tag": "before the console started"})
    logged_early = (await asyncio.to_thread(early.expect, "logged"))["messages"]

    app, live = live_app()
    try:
        async with app.run_test(size=(200, 50)) as pilot:
            # Late join: the history kept by the TRANSIENT_LOCAL rosout publisher arrives.
            await until(pilot, lambda: len(records_of(app, "e2e.early")) >= 5)
            assert [fields(r) for r in records_of(app, "e2e.early")] == logged_early
            assert [r.level for r in records_of(app, "e2e.early")] == [10, 20, 30, 40, 50]

            # A node whose rosout QoS is VOLATILE is still received.
            volatile = nodes.start("talker.py", "--name", "volatile_talker", "--volatile", "--debug")
            await asyncio.to_thread(volatile.expect, "ready")
            sent: dict[str, list] = {}
            deadline = time.monotonic() + PATIENCE_S
            while not records_of(app, "volatile_talker"):  # until the subscription matched
                assert time.monotonic() < deadline, "nothing received from a VOLATILE publisher"
                tag = f"volatile {len(sent)}"
                volatile.send({"cmd": "log_all", "tag": tag})
                sent[tag] = (await asyncio.to_thread(volatile.expect_next, "logged"))["messages"]
                with contextlib.suppress(AssertionError):  # lost before the match: send again
                    await until(pilot, lambda: records_of(app, "volatile_talker"), timeout=RESEND_S)
            all_sent = [message for batch in sent.values() for message in batch]
            # The rest of the batch that matched comes after its first message.
            await until(
                pilot,
                lambda: [fields(r) for r in records_of(app, "volatile_talker")][-1:] == all_sent[-1:],
                what="the last batch's last message",
            )
            received = [fields(r) for r in records_of(app, "volatile_talker")]
            assert received and received == all_sent[-len(received) :]  # nothing lost or doubled once matched

            # Still the live stream of the first node, in order, shown in the table.
            early.send({"cmd": "log_all", "tag": "while watching"})
            logged_live = (await asyncio.to_thread(early.expect_next, "logged"))["messages"]
            await until(pilot, lambda: len(records_of(app, "e2e.early")) >= 10)
            assert [fields(r) for r in records_of(app, "e2e.early")[5:]] == logged_live
            await until_shown(pilot, *(message["msg"] for message in logged_live))
            shown = widget_lines(app, app.main.table)[1:]  # the rows, below the header
            for message in logged_live:
                line = next(text for text in shown if message["msg"] in text)
                assert "e2e.early" in line and "talker.py" in line and str(message["line"]) in line
                assert {10: "DEBUG", 20: "INFO", 30: "WARN", 40: "ERROR", 50: "FATAL"}[message["level"]] in line
            status = app.main.sources[0].status
            assert status.topic == "/rosout" and status.publishers >= 2
    finally:
        live.close()


async def test_reads_rosout_agg_when_something_publishes_it(nodes):
    aggregator = nodes.start("aggregator.py")
    talker = nodes.start("talker.py", "--name", "agg_talker")
    await asyncio.to_thread(aggregator.expect, "ready")
    await asyncio.to_thread(talker.expect, "ready")
    await asyncio.sleep(1.0)
    app, live = live_app()
    try:
        async with app.run_test(size=(160, 30)) as pilot:
            # Chosen at start when discovery is quick, else switched to within a second.
            await until(pilot, lambda: app.main.sources[0].status.topic == "/rosout_agg")
            talker.send({"cmd": "log", "level": "warn", "msg": "through the aggregator"})
            await until(pilot, lambda: any(r.msg == "through the aggregator" for r in app.main.store))
            record = next(r for r in app.main.store if r.msg == "through the aggregator")
            assert record.source == "/rosout_agg" and record.level == 30
    finally:
        live.close()


async def test_topic_flag_picks_the_topic(nodes):
    """``--topic /rosout`` reads /rosout even while /rosout_agg has a publisher.

    Deterministic: the talkers start only once this process sees the aggregator, so the
    graph check that first counts both talkers comes after /rosout_agg was visible: a source
    that ignored the flag would be on /rosout_agg (one publisher) by then.
    """
    aggregator = nodes.start("aggregator.py")
    await asyncio.to_thread(aggregator.expect, "ready")
    app, live = live_app(topic="/rosout")
    try:
        async with app.run_test(size=(160, 30)) as pilot:
            await until(pilot, lambda: app.main.sources[0].status.running)
            probe = live.runtime.create_node("probe")
            await until(pilot, lambda: probe.count_publishers("/rosout_agg") == 1, what="the aggregator in the graph")
            talkers = [nodes.start("talker.py", "--name", f"flag_talker_{n}") for n in range(2)]
            for talker in talkers:
                await asyncio.to_thread(talker.expect, "ready")

            def settled() -> bool:
                status = screen_text(app).splitlines()[-2]
                return "/rosout_agg" in status or " /rosout 2 pubs" in status

            await until(pilot, settled, what="the status line to count both talkers")
            assert "/rosout_agg" not in screen_text(app).splitlines()[-2]
            talkers[0].send({"cmd": "log", "level": "warn", "msg": "straight on /rosout"})
            await until(pilot, lambda: "straight on /rosout" in screen_text(app), what="the message on the screen")
            assert " WARN " in line_with(app, "straight on /rosout")[1]
            assert [r.source for r in app.main.store if r.msg == "straight on /rosout"] == ["/rosout"]
            assert " /rosout 2 pubs" in screen_text(app).splitlines()[-2]
    finally:
        live.close()


def test_without_ros_a_clear_message_and_no_traceback():
    code = "import sys; sys.modules['rclpy'] = None; from console_tui.cli import main; sys.exit(main([]))"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert result.returncode == 2
    assert "source your ROS 2 install" in result.stderr and "console-tui[ros]" in result.stderr
    assert "Traceback" not in result.stderr
