"""The logger levels pane end to end: the real app, a real LoggerControl, real rclpy talkers.

Levels are set with the pane's keys and checked where it matters: in the node's messages
reaching the table. Ordering makes the checks deterministic: a talker's messages arrive in
the order it logged them, so once a marker logged after a level change is in the table,
everything logged before the change is too.
"""

from __future__ import annotations

import asyncio

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.ui.app import ConsoleApp
from console_tui.ui.screens.temporary_level import TemporaryLevelScreen

from support.ui import option_lines, pick_node, until

pytestmark = pytest.mark.ros2

TALKER = "/ns/talker"


@pytest.fixture
def live(ros_runtime):
    """A ConsoleApp reading /rosout with a LoggerControl on the test's runtime; closed after."""
    from console_tui.control.ros2.logger_control import Ros2LoggerControl
    from console_tui.sources.ros2.live_source import LiveLogSource

    queue = IntakeQueue()
    control = Ros2LoggerControl(ros_runtime, call_timeout=2.0)
    app = ConsoleApp(
        queue=queue, sources=[LiveLogSource(ros_runtime, queue, topic="/rosout")], utc=True, logger_control=control
    )
    yield app
    control.close()


def row_of(pane, logger_label: str) -> str:
    return next((line for line in option_lines(pane.logger_list) if line.split()[0:1] == [logger_label]), "")


def notice(pane) -> str:
    return pane.state.notice_text()[0]


def messages(app, node: str) -> list:
    return [record for record in app.main.store if record.node == node]


async def log_marker(app, pilot, talker, tag: str) -> tuple[list, object]:
    """Log one message at each severity; returns (records from before it, its INFO record)."""
    talker.send({"cmd": "log_all", "tag": tag})
    await asyncio.to_thread(talker.expect_next, "logged")
    info = f"{tag} info message"
    await until(pilot, lambda: any(r.msg == info for r in app.main.store), what=info)
    marker = next(r for r in app.main.store if r.msg == info)
    return [r for r in messages(app, "ns.talker") if r.seq < marker.seq], marker


async def start_talkers(nodes, *extra: list[str]):
    talker = nodes.start("talker.py", "--name", "talker", "--namespace", "/ns")
    others = [nodes.start("talker.py", *args) for args in extra]
    for process in [talker, *others]:
        await asyncio.to_thread(process.expect, "ready")
    return talker, others


async def open_logger_pane(app, pilot, ready, what: str):
    """Opens the logger pane (``l``) and lets the app run until ``ready(pane)``; returns the pane."""
    pane = app.main.logger_pane
    await pilot.press("l")
    await until(pilot, lambda: ready(pane), what=what)
    return pane


async def test_pane_lists_nodes_marks_one_without_services_and_debug_on_then_off(nodes, live):
    talker, _ = await start_talkers(nodes, ["--name", "plain", "--no-logger-service"])
    talker.send({"cmd": "periodic", "period": 0.1})
    app = live
    async with app.run_test(size=(160, 40)) as pilot:
        pane = app.main.logger_pane
        await until(pilot, lambda: any(r.msg.startswith("tick") for r in app.main.store), what="the talker's ticks")
        assert not any(r.level == 10 for r in messages(app, "ns.talker")), "DEBUG is off by default"

        # The key on a table row opens the pane on that row's node, its logger highlighted: the
        # app joins the graph then, and selects the node once the graph shows it.
        await pilot.press("L")
        assert pane.is_open
        await until(pilot, lambda: pane.selected == TALKER, what="the row's node selected")
        await until(pilot, lambda: {n.fqn for n in pane.nodes} >= {TALKER, "/plain"}, what="the nodes")
        await until(pilot, lambda: pane.highlighted_logger == "ns.talker", what="the row's logger highlighted")
        assert pane.logger_list.has_focus
        await until(pilot, lambda: "inherited (INFO)" in row_of(pane, "ns.talker"), what="levels read")
        assert '"" (default)' in " ".join(option_lines(pane.logger_list))

        # The node without logger services: "checking" at first, then marked, with the hint.
        await until(
            pilot,
            lambda: any("/plain" in line and "no logger services" in line for line in option_lines(pane.node_list)),
            what="the mark",
        )
        await pilot.press("left")
        assert pane.node_list.has_focus
        await pilot.press("down")
        assert pane.selected == "/plain"
        assert "enable_logger_service=True" in notice(pane) and "enable_logger_service(true)" in notice(pane)
        assert pane.rows() == []

        # DEBUG by key: the talker's DEBUG ticks reach the table.
        await pilot.press("up", "right", "d")
        await until(pilot, lambda: row_of(pane, "ns.talker").endswith("DEBUG"), what="DEBUG shown")
        before, marker = await log_marker(app, pilot, talker, "debug-on")
        assert any(r.msg == "debug-on debug message" and r.level == 10 for r in before)
        await until(
            pilot,
            lambda: any(r.level == 10 and r.msg.startswith("tick") and r.seq > marker.seq for r in app.main.store),
            what="DEBUG ticks",
        )

        # Back to INFO by key: no DEBUG message after the change.
        await pilot.press("i")
        await until(pilot, lambda: row_of(pane, "ns.talker").endswith("INFO"), what="INFO shown")
        _, marker = await log_marker(app, pilot, talker, "debug-off")
        await until(
            pilot,
            lambda: (
                len([r for r in messages(app, "ns.talker") if r.seq > marker.seq and r.msg.startswith("tick")]) >= 6
            ),
            what="more ticks",
        )
        after = [r for r in messages(app, "ns.talker") if r.seq >= marker.seq]
        assert not any(r.level == 10 for r in after), [r.msg for r in after if r.level == 10]
        assert not any(r.msg == "debug-off debug message" for r in app.main.store)

        # Escape gives the table the keys back; the table still follows while the pane is open.
        await pilot.press("escape")
        assert app.main.table.has_focus and pane.is_open and app.main.table.following
        await pilot.press("l")
        assert not pane.is_open


async def test_temporary_debug_counts_down_and_reverts(nodes, live):
    talker, _ = await start_talkers(nodes)
    talker.send({"cmd": "periodic", "period": 0.1})
    app = live
    async with app.run_test(size=(160, 40)) as pilot:
        pane = await open_logger_pane(
            app,
            pilot,
            lambda pane: pane.selected == TALKER and "inherited" in row_of(pane, "ns.talker"),
            what="the talker's levels",
        )
        await pilot.press("right", "t")
        assert isinstance(app.screen, TemporaryLevelScreen)
        await pilot.press("3", "enter")  # DEBUG is the level offered first; the 30 is selected, so typing replaces it
        seen: list[str] = []

        def row() -> str:
            text = row_of(pane, "ns.talker")
            if "DEBUG for" in text and text not in seen:
                seen.append(text)
            return text

        await until(pilot, lambda: "DEBUG for" in row(), what="the countdown")
        await until(
            pilot,
            lambda: row() and any(r.level == 10 and r.msg.startswith("tick") for r in app.main.store),
            what="DEBUG ticks",
        )
        await until(pilot, lambda: "DEBUG for" not in row(), timeout=15, what="the end of the temporary level")
        seconds = [int(row.rsplit("for", 1)[1].strip().rstrip("s")) for row in seen]
        assert seconds == sorted(seconds, reverse=True) and seconds[0] <= 3
        await until(pilot, lambda: "inherited" in row_of(pane, "ns.talker"), what="the level put back")
        assert "back to inherited" in notice(pane)
        assert app.logger_control.temporaries() == ()
        _, marker = await log_marker(app, pilot, talker, "after")
        await until(
            pilot, lambda: len([r for r in messages(app, "ns.talker") if r.seq > marker.seq]) >= 6, what="more ticks"
        )
        assert not any(r.level == 10 for r in messages(app, "ns.talker") if r.seq >= marker.seq)


async def test_node_killed_during_a_call_gives_a_clear_message_and_the_app_carries_on(nodes, live):
    talker, (other,) = await start_talkers(nodes, ["--name", "other"])
    app = live
    async with app.run_test(size=(160, 40)) as pilot:
        pane = await open_logger_pane(
            app,
            pilot,
            lambda pane: (
                {n.fqn for n in pane.nodes} >= {TALKER, "/other"} and all(n.has_logger_services for n in pane.nodes)
            ),
            what="the nodes",
        )
        await pick_node(pilot, TALKER)
        await until(pilot, lambda: "inherited" in row_of(pane, "ns.talker"), what="the talker's levels")
        talker.send({"cmd": "block", "seconds": 30})
        await asyncio.to_thread(talker.expect, "blocking")
        await pilot.press("right", "d")
        assert pane.state.pending.get(TALKER)
        talker.kill()
        await until(pilot, lambda: "Could not set ns.talker to DEBUG" in notice(pane), timeout=10, what="the failure")
        assert TALKER in notice(pane)
        assert "went away during the call" in notice(pane) or "did not answer within 2 s" in notice(pane)

        # The app carries on: the other node's level is set, with a click on the level bar.
        await pilot.press("left", "down")
        assert pane.selected == "/other"
        await until(pilot, lambda: "inherited" in row_of(pane, "other"), what="the other node's levels")
        await pilot.click("#logger-level-bar", offset=(len("DEBUG INFO "), 0))
        await until(pilot, lambda: row_of(pane, "other").endswith("WARN"), what="WARN set")
        assert "other set to WARN" in notice(pane)
        other.send({"cmd": "log", "level": "warn", "msg": "still here"})  # and the table still follows
        await until(pilot, lambda: any(r.msg == "still here" for r in app.main.store), what="the other node's message")
        assert app.main.table.following and app.main.table.cursor_row == app.main.table.row_count - 1
