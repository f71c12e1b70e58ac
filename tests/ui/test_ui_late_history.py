"""Histories that arrive late (a ROS 2 publisher's /rosout history at start, a fleet's robot
that joins late) are placed by their stamps while the table follows the tail; once the user
scrolled, nothing moves under the reader. A stand-in live source (no ROS): the records are
put on the app's intake queue as a live source's intake puts them."""

from __future__ import annotations

import re

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.ros.fleet import Robot
from console_tui.ros.ros_version import ROS2
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp

from support.feed import BASE_NS, StaticSource
from support.ui import screen_text, table_rows, until

_STAMP = re.compile(r"t=(\d+\.\d+)")


class Clock:
    """The app's clock, moved by the test only (histories are due for a while after a change)."""

    def __init__(self) -> None:
        self.now = 1000.0

    def __call__(self) -> float:
        return self.now


def live_app(robots: list[Robot] | None = None, clock: Clock | None = None) -> tuple[ConsoleApp, IntakeQueue]:
    queue = IntakeQueue()
    names = [robot.name for robot in robots] if robots else [""]
    sources = [StaticSource(SourceStatus(topic="/rosout", publishers=2, running=True, robot=name)) for name in names]
    app = ConsoleApp(
        store=LogStore(), queue=queue, sources=sources, utc=True, robots=robots or [], clock=clock or Clock()
    )
    return app, queue


def put(queue: IntakeQueue, node: str, count: int, start_s: float, step_s: float, robot: str = "") -> None:
    """``count`` messages of ``node`` from ``start_s``, ``step_s`` apart: each says its stamp."""
    batch = RecordColumns.from_records(
        [
            LogRecord(BASE_NS + round((start_s + i * step_s) * 1e9), 20, node, f"{node} t={start_s + i * step_s:07.3f}")
            for i in range(count)
        ]
    )
    queue.put(batch.of_robot(robot) if robot else batch)


def shown_stamps(app) -> list[float]:
    """The stamps the table's rows on the screen say, top to bottom."""
    rows = sorted(table_rows(app).values())
    return [float(found.group(1)) for _, line in rows if (found := _STAMP.search(line))]


def status_line(app) -> str:
    """The status bar: the terminal's last row but one."""
    return screen_text(app).splitlines()[-2]


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_histories_at_start_are_placed_by_their_stamps(size):
    app, queue = live_app()
    async with app.run_test(size=size) as pilot:
        put(queue, "/talker", 8, 10.0, 0.5)  # the first publisher's history: 10.0 .. 13.5 s
        await until(pilot, lambda: "t=013.500" in screen_text(app), what="the first history")
        put(queue, "/listener", 8, 8.25, 0.5)  # the second one's, arriving after: 8.25 .. 11.75 s
        await until(pilot, lambda: "16/16 shown" in status_line(app), what=lambda: status_line(app))
        stamps = shown_stamps(app)
        assert len(stamps) == 16, screen_text(app)
        assert stamps == sorted(stamps), screen_text(app)
        assert "FOLLOW" in status_line(app)


async def test_a_late_history_does_not_move_rows_once_the_user_scrolled():
    app, queue = live_app()
    async with app.run_test(size=(100, 30)) as pilot:
        put(queue, "/talker", 200, 10.0, 0.1)
        await until(pilot, lambda: "200/200 shown" in status_line(app), what="the records")
        await pilot.press("pageup")
        await until(pilot, lambda: "SCROLL" in status_line(app), what="SCROLL")
        before = {number: line[:-2] for number, (_, line) in table_rows(app).items()}  # less the scrollbar
        put(queue, "/late", 30, 5.0, 0.5)  # 5.0 .. 19.5 s: among the rows on the screen
        await until(pilot, lambda: "230/230 shown" in status_line(app), what=lambda: status_line(app))
        assert {number: line[:-2] for number, (_, line) in table_rows(app).items()} == before
        assert "/late" not in screen_text(app)


async def test_a_robot_that_joins_late_has_its_history_placed_by_stamp():
    robots = [Robot("picker", ROS2, domain=3), Robot("forklift", ROS2, domain=4)]
    app, queue = live_app(robots)
    async with app.run_test(size=(100, 30)) as pilot:
        put(queue, "/talker", 8, 10.0, 0.5, robot="picker")
        await until(pilot, lambda: "t=013.500" in screen_text(app), what="the first robot")
        put(queue, "/planner", 8, 9.75, 0.5, robot="forklift")  # joins late with its history
        await until(pilot, lambda: "16/16 shown" in status_line(app), what=lambda: status_line(app))
        stamps = shown_stamps(app)
        assert len(stamps) == 16 and stamps == sorted(stamps), screen_text(app)
        assert "forklift" in screen_text(app)


async def test_robots_whose_clocks_differ_are_shown_as_they_come_once_their_histories_are_in():
    """Outside the moments histories come (a source starting, a publisher joining), a batch
    older than the newest rows is a clock that differs, not a history: nothing is rewritten."""
    robots = [Robot("picker", ROS2, domain=3), Robot("forklift", ROS2, domain=4)]
    clock = Clock()
    app, queue = live_app(robots, clock)
    async with app.run_test(size=(100, 30)) as pilot:
        put(queue, "/talker", 4, 10.0, 0.5, robot="picker")
        await until(pilot, lambda: "t=011.500" in screen_text(app), what="the first robot")
        clock.now += 60  # long after the start: forklift's clock is 5 s behind picker's
        put(queue, "/planner", 4, 7.0, 0.5, robot="forklift")
        await until(pilot, lambda: "8/8 shown" in status_line(app), what=lambda: status_line(app))
        assert shown_stamps(app) == [10.0, 10.5, 11.0, 11.5, 7.0, 7.5, 8.0, 8.5], screen_text(app)
        app.main.sources[1].status.publishers += 1  # a node joins forklift's graph with its history
        put(queue, "/joined", 2, 6.0, 0.1, robot="forklift")
        await until(pilot, lambda: "10/10 shown" in status_line(app), what=lambda: status_line(app))
        assert shown_stamps(app) == sorted(shown_stamps(app)), screen_text(app)  # placed: a history
        assert shown_stamps(app)[:2] == [6.0, 6.1], screen_text(app)
