"""A fleet on the screen, without ROS: the Robot column (shown with more than one robot), its
colours, ``robot:`` in the query line, the robots' states on the status line, the node panel's
nodes per robot and the summary's counts per robot."""

from __future__ import annotations

import re

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.ros.fleet import Robot
from console_tui.ros.ros_version import ROS1, ROS2
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp

from support.feed import StaticSource
from support.ui import cursor_line, line_with, run_command, screen_text, table_rows, type_text, until

ROBOTS = [Robot("picker", ROS2, domain=3, colour="cyan"), Robot("forklift", ROS1, master="http://127.0.0.1:1/")]


def fleet_app(**options) -> tuple[ConsoleApp, IntakeQueue]:
    queue = IntakeQueue()
    sources = [
        StaticSource(SourceStatus(topic="/rosout", publishers=1, running=True, robot="picker")),
        StaticSource(SourceStatus(topic="/rosout", running=True, robot="forklift")),
    ]
    app = ConsoleApp(store=LogStore(), queue=queue, sources=sources, utc=True, robots=ROBOTS, **options)
    return app, queue


def put(queue: IntakeQueue, robot: str, count: int, start: int = 0) -> None:
    records = [
        LogRecord(
            1_700_000_000_000_000_000 + (start + i) * 1_000_000, 20 + 10 * (i % 2), "/talker", f"{robot} says {i}"
        )
        for i in range(count)
    ]
    queue.put(RecordColumns.from_records(records).of_robot(robot))


async def node_panel_over(pilot, app, queue: IntakeQueue, *, picker: int, forklift: int) -> None:
    """Both robots' ``/talker`` messages on the screen, then the node panel open."""
    put(queue, "picker", picker)
    put(queue, "forklift", forklift, start=10)
    await until(pilot, lambda: f"forklift says {forklift - 1}" in screen_text(app), what="the rows")
    await pilot.press("ctrl+n")
    await until(pilot, lambda: "Nodes: 2" in screen_text(app), what="the node panel")


def header(app) -> str:
    return screen_text(app).splitlines()[app.main.table.region.y]


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_each_row_says_its_robot_and_robot_filters(size):
    app, queue = fleet_app()
    async with app.run_test(size=size) as pilot:
        put(queue, "picker", 4)
        put(queue, "forklift", 4, start=10)
        await until(pilot, lambda: "forklift says 3" in screen_text(app), what="the rows")
        assert "Robot" in header(app)
        assert "picker✓ forklift…" in screen_text(app)
        rows = [line for _, line in table_rows(app).values()]
        assert sum("picker" in line and "picker says" in line for line in rows) == 4
        assert sum(line.count("forklift") == 2 for line in rows) == 4
        await pilot.press("slash")
        await type_text(pilot, "robot:picker")
        await pilot.press("enter")
        await until(pilot, lambda: "forklift says" not in screen_text(app), what="the filter")
        assert "picker says 3" in screen_text(app)
        await pilot.press("enter")
        await until(pilot, lambda: "Robot" in screen_text(app) and "Stamp" in screen_text(app), what="the details")
        assert re.search(r"Robot +picker\b", screen_text(app))


async def test_a_robots_colour_paints_its_name():
    app, queue = fleet_app()
    async with app.run_test(size=(100, 30)) as pilot:
        put(queue, "picker", 1)
        put(queue, "forklift", 1, start=5)
        await until(pilot, lambda: "forklift says 0" in screen_text(app), what="the rows")
        picker = app.main.table.painter.robot_styles["picker"]
        assert picker.color is not None and picker.color.name == "cyan"
        assert "forklift" not in app.main.table.painter.robot_styles


async def test_the_node_panel_and_the_summary_count_per_robot():
    app, queue = fleet_app()
    async with app.run_test(size=(120, 34)) as pilot:
        await node_panel_over(pilot, app, queue, picker=4, forklift=6)
        assert line_with(app, "picker: /talker")[1].split("▏")[1].split()[3:5] == ["2", "2"]
        assert line_with(app, "forklift: /talker")[1].split("▏")[1].split()[3:5] == ["3", "3"]
        await pilot.press("ctrl+n", "S")
        await until(pilot, lambda: "Robots" in screen_text(app), what="the summary")
        assert line_with(app, "robot picker (receiving)")
        assert line_with(app, "robot forklift (waiting)")
        assert re.search(r"  forklift +0 +3 +3 +0 +0 +6", screen_text(app))
        assert re.search(r"  picker +0 +2 +2 +0 +0 +4", screen_text(app))


async def test_one_source_shows_no_robot_column():
    app = ConsoleApp(store=LogStore(), utc=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        assert "Robot" not in header(app)


async def test_what_the_robots_sent_meanwhile_shows_in_time_order():
    app, queue = fleet_app()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        base = 1_700_000_000_000_000_000
        picker = [LogRecord(base + i * 2_000_000, 20, "/talker", f"picker {i}") for i in range(3)]
        cart = [LogRecord(base + i * 2_000_000 + 1_000_000, 20, "/talker", f"cart {i}") for i in range(3)]
        queue.put(RecordColumns.from_records(picker).of_robot("picker"))  # one tick's batches
        queue.put(RecordColumns.from_records(cart).of_robot("cart"))
        await until(pilot, lambda: "cart 2" in screen_text(app), what="the rows")
        shown = [line.split()[-2:] for _, line in sorted(table_rows(app).values())]
        assert shown == [["picker", "0"], ["cart", "0"], ["picker", "1"], ["cart", "1"], ["picker", "2"], ["cart", "2"]]


async def test_solo_and_mute_act_on_one_robots_node():
    """The same node name on two robots is two nodes: soloing picker's /talker leaves
    forklift's /talker out, and muting it from a row hides that robot's only."""
    app, queue = fleet_app()
    async with app.run_test(size=(120, 34)) as pilot:
        await node_panel_over(pilot, app, queue, picker=4, forklift=4)
        for _ in range(2):
            if app.main.node_pane.highlighted_option_id == "picker: /talker":
                break
            await pilot.press("down")
        await pilot.press("s")
        await until(pilot, lambda: "forklift says" not in screen_text(app), what="the solo")
        assert "picker says 3" in screen_text(app)
        assert "solo picker:/talker" in screen_text(app)
        assert re.search(r"▏ S picker: /talker", screen_text(app))
        assert re.search(r"▏ +forklift: /talker", screen_text(app))
        await pilot.press("x", "escape")
        await until(pilot, lambda: "forklift says 3" in screen_text(app), what="every node again")
        await until(pilot, lambda: cursor_line(app) is not None, what="the table's cursor")
        for _ in range(8):
            if "forklift" in cursor_line(app):
                break
            await pilot.press("up")  # to a row of forklift's
        await run_command(pilot, "Mute this row's node")
        await until(pilot, lambda: "forklift says" not in screen_text(app), what="the mute")
        assert "picker says 3" in screen_text(app)
        await until(pilot, lambda: "muted forklift:/talker" in screen_text(app), what="the status line")
