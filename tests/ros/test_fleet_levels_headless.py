"""Logger levels and the headless commands across a fleet, end to end: two ROS 2 domains, a
talker of the same name on each; DEBUG set in the pane on one robot's talker reaches that robot's
messages and never the other's; ``console-tui loggers`` names the robots' nodes apart;
``console-tui tail`` says each line's robot."""

from __future__ import annotations

import asyncio
import time

import pytest
from conftest import next_domain_id

from console_tui.control.fleet_control import open_fleet_loggers
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.live import open_fleet
from console_tui.ui.app import ConsoleApp

from support.fleet import ROS2_VALUES, LoopbackFleet
from support.rosproc import ros_available
from support.ui import option_lines, pick_node, until

pytestmark = pytest.mark.ros2

DEADLINE_S = 120.0


@pytest.fixture
def two_domains(monkeypatch):
    if not ros_available():
        pytest.skip("rclpy is not installed (pip install -e '.[ros]')")
    for key, value in ROS2_VALUES.items():
        monkeypatch.setenv(key, value)
    monkeypatch.delenv("ROS_LOCALHOST_ONLY", raising=False)
    domains: list[int] = []
    while len(domains) < 2 and len(domains) < 64:
        domain = next_domain_id()
        if domain not in domains:
            domains.append(domain)
    made = LoopbackFleet()
    try:
        for name, domain in zip(("left", "right"), domains, strict=True):
            made.add_domain(name, domain, "talker")
        yield made
    finally:
        made.stop()


def debug_ticks(app: ConsoleApp, robot: str, after: int) -> list:
    return [r for r in app.main.store if r.robot == robot and r.level == 10 and r.seq > after]


async def test_debug_on_one_robots_node_and_not_the_same_name_on_another(two_domains):
    for member in two_domains.robots:
        member.node.send({"cmd": "periodic", "period": 0.2})
    robots = [member.robot for member in two_domains.robots]
    queue = IntakeQueue()
    lives = open_fleet(queue, robots)
    cleanups: list = []
    control = open_fleet_loggers(robots, cleanups)
    app = ConsoleApp(
        queue=queue, sources=[live.source for live in lives], utc=True, robots=robots, logger_control=control
    )
    try:
        async with app.run_test(size=(160, 40)) as pilot:
            await until(
                pilot,
                lambda: {r.robot for r in app.main.store if r.msg.startswith("tick")} == {"left", "right"},
                timeout=DEADLINE_S,
                what="both robots' ticks",
            )
            assert not any(r.level == 10 for r in app.main.store), "DEBUG is off by default"
            pane = app.main.logger_pane
            await pilot.press("l")
            # The app joins both robots' graphs as the pane opens: their nodes come as found.
            await until(
                pilot,
                lambda: all(
                    any(fqn in line for line in option_lines(pane.node_list))
                    for fqn in ("left:/talker", "right:/talker")
                ),
                timeout=DEADLINE_S,
                what="both robots' talkers shown in the pane",
            )
            await pick_node(pilot, "left:/talker")
            await pilot.press("right")  # to its loggers, its own ("talker") highlighted
            assert pane.logger_list.has_focus and pane.highlighted_logger == "talker"
            await until(
                pilot,
                lambda: any(
                    line.split()[:1] == ["talker"] and "INFO" in line for line in option_lines(pane.logger_list)
                ),
                timeout=DEADLINE_S,
                what="the left talker's levels read",
            )
            marker = app.main.store.end_seq
            await pilot.press("d")
            await until(
                pilot,
                lambda: any(
                    line.split()[:1] == ["talker"] and line.endswith("DEBUG") for line in option_lines(pane.logger_list)
                ),
                timeout=DEADLINE_S,
                what="DEBUG shown",
            )
            await until(
                pilot, lambda: len(debug_ticks(app, "left", marker)) >= 3, timeout=DEADLINE_S, what="DEBUG ticks"
            )
            # The other robot's talker of the same name went on at INFO: later ticks, none DEBUG.
            after = app.main.store.end_seq
            await until(
                pilot,
                lambda: len([r for r in app.main.store if r.robot == "right" and r.seq > after]) >= 3,
                timeout=DEADLINE_S,
                what="more ticks from the right",
            )
            assert debug_ticks(app, "right", 0) == []
            right = two_domains.robots[1].node
            await asyncio.to_thread(right.send, {"cmd": "log", "level": "debug", "msg": "right debug"})
            await asyncio.to_thread(right.expect_next, "logged", 60)
            await asyncio.to_thread(right.send, {"cmd": "log", "level": "info", "msg": "right marker"})
            await asyncio.to_thread(right.expect_next, "logged", 60)
            await until(pilot, lambda: any(r.msg == "right marker" for r in app.main.store), timeout=DEADLINE_S)
            assert not any(r.msg == "right debug" for r in app.main.store)  # logged before the marker, in order
    finally:
        for live in lives:
            live.close()
        control.close()
        for cleanup in reversed(cleanups):
            cleanup()


def test_loggers_command_across_a_fleet(two_domains, capsys):
    from console_tui.commands import loggers

    fleet = [f"--domain={member.robot.domain}={member.robot.name}" for member in two_domains.robots]
    assert loggers.main(["list", "--wait", "20", *fleet]) == 0
    listed = capsys.readouterr().out
    assert "left:/talker" in listed and "right:/talker" in listed
    assert loggers.main(["get", "--wait", "20", *fleet, "/talker"]) == 2  # on both robots: which?
    assert "left:/talker, right:/talker" in capsys.readouterr().err
    assert loggers.main(["set", "--wait", "20", *fleet, "left:/talker", "talker", "debug"]) == 0
    assert loggers.main(["get", "--wait", "20", *fleet, "--robot", "left", "/talker", "talker"]) == 0
    assert capsys.readouterr().out.splitlines()[-1].split()[:2] == ["talker", "DEBUG"]
    assert loggers.main(["get", "--wait", "20", *fleet, "--robot", "right", "/talker", "talker"]) == 0
    assert capsys.readouterr().out.splitlines()[-1].split()[:2] == ["talker", "inherited"]
    assert loggers.main(["get", *fleet, "--robot", "nobody", "/talker"]) == 2
    assert "no such robot" in capsys.readouterr().err


def test_tail_across_a_fleet_names_each_line_robot(two_domains):
    import os

    from support.tail_process import TailProcess

    fleet = [f"--domain={member.robot.domain}={member.robot.name}" for member in two_domains.robots]
    tail = TailProcess(dict(os.environ), *fleet, "--query", "tick", "--format", "{robot}|{name}|{message}")
    try:
        for member in two_domains.robots:
            member.node.send({"cmd": "periodic", "period": 0.2})
        robots: set[str] = set()
        deadline = time.monotonic() + DEADLINE_S
        while robots != {"left", "right"} and time.monotonic() < deadline:
            for line in tail.take_text(1, timeout=max(deadline - time.monotonic(), 0.1)):
                robot, name, message = line.split("|", 2)
                assert name == "talker" and message.startswith("tick")
                robots.add(robot)
        assert robots == {"left", "right"}, tail.stderr
    finally:
        assert tail.stop() == 0
