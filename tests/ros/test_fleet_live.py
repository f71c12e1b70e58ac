"""A fleet end to end on loopback: three ROS 2 domains and two ROS 1 masters (Debian's roscore,
rospy nodes), every node with the same name; one console (the app, headless) shows each robot's
messages with its robot, ``robot:`` filters, and a master stopped and a domain's node killed
leave the others receiving."""

from __future__ import annotations

import asyncio

import pytest
from conftest import next_domain_id

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.live import open_fleet
from console_tui.ui.app import ConsoleApp

from support.fleet import ROS2_VALUES, FleetRobot, LoopbackFleet
from support.ros1 import ros1_missing
from support.rosproc import ros_available
from support.ui import screen_text, table_rows, type_text, until

pytestmark = [pytest.mark.ros2, pytest.mark.ros1]

#: Generous: five intake processes, three rclpy nodes and two roscores start on a busy machine.
DEADLINE_S = 120.0


def distinct_domains(count: int) -> list[int]:
    """``count`` domains of this test's share of the range, all different."""
    domains: list[int] = []
    for _ in range(64):
        domain = next_domain_id()
        if domain not in domains:
            domains.append(domain)
        if len(domains) == count:
            return domains
    pytest.skip(f"CONSOLE_TUI_TEST_DOMAINS gives this worker fewer than {count} domains")


@pytest.fixture
def fleet(tmp_path, monkeypatch):
    if not ros_available():
        pytest.skip("rclpy is not installed (pip install -e '.[ros]')")
    reason = ros1_missing()
    if reason:
        pytest.skip(reason)
    for key, value in ROS2_VALUES.items():
        monkeypatch.setenv(key, value)
    monkeypatch.setenv("ROS_IP", "127.0.0.1")  # what the ROS 1 intakes advertise
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    monkeypatch.delenv("ROS_LOCALHOST_ONLY", raising=False)
    made = LoopbackFleet()
    try:
        for number, domain in enumerate(distinct_domains(3)):
            made.add_domain(f"r2{'abc'[number]}", domain, "talker")
        for number in range(2):
            made.add_master(f"r1{'ab'[number]}", tmp_path / f"master{number}", "talker")
        yield made
    finally:
        made.stop()


def robots_of(app: ConsoleApp, text: str) -> set[str]:
    return {record.robot for record in app.main.store if record.msg == text}


async def logged_and_seen(pilot, app: ConsoleApp, robot: FleetRobot, text: str) -> None:
    """``robot``'s node logs ``text`` until the console has it (a ROS 1 intake may join after
    the first line), from that robot only."""
    name = robot.robot.name
    for _ in range(int(DEADLINE_S)):
        await asyncio.to_thread(robot.log, text)
        try:
            await until(pilot, lambda: name in robots_of(app, text), timeout=3.0)
            break
        except AssertionError:
            continue
    else:
        raise AssertionError(f"{name} never delivered {text!r}: {app.main.sources[0].status}")
    assert robots_of(app, text) == {name}


async def test_five_robots_in_one_console(fleet):
    queue = IntakeQueue()
    robots = [member.robot for member in fleet.robots]
    lives = open_fleet(queue, robots)
    app = ConsoleApp(queue=queue, sources=[live.source for live in lives], utc=True, robots=robots)
    try:
        async with app.run_test(size=(140, 45)) as pilot:
            for member in fleet.robots:
                await logged_and_seen(pilot, app, member, f"hello from {member.robot.name}")

            def every_hello() -> bool:
                rows = [line for _, line in table_rows(app).values()]
                return all(any(f"hello from {m.robot.name}" in line for line in rows) for m in fleet.robots)

            await until(pilot, every_hello, what="each robot's hello in a row on the screen")
            rows = [line for _, line in table_rows(app).values()]
            for member in fleet.robots:
                name = member.robot.name
                row = next(line for line in rows if f"hello from {name}" in line)
                assert row.split()[3] == name, row  # # Time Sev Robot Node Message
            statuses = {source.status.robot: source.status for source in app.main.sources}
            assert set(statuses) == {"r2a", "r2b", "r2c", "r1a", "r1b"}
            assert all(status.problem == "" for status in statuses.values()), statuses
            # Two nodes of one name on two robots: the node panel counts them apart.
            app.main.node_stats.update()
            assert len({entry.label for entry in app.main.node_stats.nodes()}) >= 5

            # robot: filters.
            await pilot.press("slash")
            await type_text(pilot, "robot:r2b,r1a")
            await pilot.press("enter")
            await until(pilot, lambda: "hello from r2a" not in screen_text(app), what="the filter")
            text = screen_text(app)
            assert "hello from r2b" in text and "hello from r1a" in text
            assert not any(f"hello from {n}" in text for n in ("r2a", "r2c", "r1b"))
            await pilot.press("slash", "end", "ctrl+u", "enter")
            await until(pilot, lambda: "hello from r2a" in screen_text(app), what="the filter gone")

            # One master and one domain's node die: the others keep coming.
            by_name = {member.robot.name: member for member in fleet.robots}
            by_name["r1a"].master.stop()
            by_name["r2a"].node.kill()
            for name in ("r2b", "r2c", "r1b"):
                await logged_and_seen(pilot, app, by_name[name], f"still there, {name}")
            await until(
                pilot,
                lambda: "still there, r1b" in screen_text(app) and "still there, r2c" in screen_text(app),
                timeout=DEADLINE_S,
                what="the survivors' rows",
            )
            status_line = screen_text(app).splitlines()[app.main.status_bar.region.y]
            for name in ("r2b", "r2c", "r1b"):
                assert name in status_line
    finally:
        for live in lives:
            live.close()
