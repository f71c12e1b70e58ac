"""``console-tui ship`` end to end on loopback, with real nodes in real processes: two ROS 2
robots (domains) and a ROS 1 robot (a roscore, a rospy node), each shipping through a real
collector (rotel) to a receiver that counts what arrives; the same three robots shipped into
chDB, read back by ``console-tui tail`` and in the table app."""

from __future__ import annotations

import asyncio
import json
import os
import subprocess
import sys

import pytest

from console_tui.model.store.log_store import LogStore
from console_tui.sources.warehouse_source import WarehouseSource
from console_tui.ui.app import ConsoleApp
from console_tui.warehouse.address import parse_address

from support.fleet import ROS2_VALUES, LoopbackFleet
from support.otlp_receiver import OtlpReceiver
from support.ros1 import ros1_missing
from support.rosproc import PATIENCE_S, ros_available, wait_until
from support.rotel import ROTEL_MISSING, Rotel
from support.ship_process import ShipProcess, number_after
from support.ui import table_rows, until
from support.warehouse import STORE_MISSING

pytestmark = [pytest.mark.ros2, pytest.mark.ros1]

LEVELS = {
    "debug": (5, "DEBUG"),
    "info": (9, "INFO"),
    "warn": (13, "WARN"),
    "error": (17, "ERROR"),
    "fatal": (21, "FATAL"),
}


@pytest.fixture
def fleet(tmp_path, monkeypatch):
    """Two ROS 2 robots on two domains of this test's range and one ROS 1 robot."""
    from test_fleet_live import distinct_domains

    if not ros_available():
        pytest.skip("rclpy is not installed (pip install -e '.[ros]')")
    reason = ros1_missing() or STORE_MISSING or ROTEL_MISSING
    if reason:
        pytest.skip(reason)
    for key, value in ROS2_VALUES.items():
        monkeypatch.setenv(key, value)
    monkeypatch.setenv("ROS_IP", "127.0.0.1")
    monkeypatch.delenv("ROS_HOSTNAME", raising=False)
    monkeypatch.delenv("ROS_LOCALHOST_ONLY", raising=False)
    made = LoopbackFleet()
    try:
        for name, domain in zip(("picker", "cart"), distinct_domains(2), strict=True):
            made.add_domain(name, domain, "talker")
        made.add_master("forklift", tmp_path / "master", "talker")
        yield made
    finally:
        made.stop()


def robot_env(robot) -> dict[str, str]:
    env = robot.robot.environment()
    env.pop("ROS_LOCALHOST_ONLY", None)
    return env


def reading(line: str) -> bool:
    """A status line saying the shipper's source has found a publisher."""
    return "reading /rosout" in line and "(0 publishers)" not in line


def log_known(fleet: LoopbackFleet, tag: str) -> dict[str, list[dict]]:
    """Each robot logs one message at each severity from INFO up; what each logged, by robot."""
    logged: dict[str, list[dict]] = {}
    for robot in fleet.robots:
        if robot.master is None:
            robot.node.send({"cmd": "log_all", "tag": f"{tag} {robot.robot.name}"})
            messages = robot.node.expect_next("logged", 60)["messages"]
            logged[robot.robot.name] = [m for m in messages if m["level"] >= 20]  # its logger is at INFO
        else:
            logged[robot.robot.name] = []
            for level in list(LEVELS)[1:]:  # rospy's node logs at INFO
                text = f"{tag} {robot.robot.name} {level} message"
                robot.node.send({"log": level, "msg": text})
                robot.node.expect_next("logged", 60)
                logged[robot.robot.name].append({"msg": text, "level_name": level})
    return logged


def test_three_robots_through_a_collector_each_message_once_with_every_field(fleet, tmp_path):
    receiver = OtlpReceiver()
    collector = Rotel(receiver.url, tmp_path)
    ships = []
    try:
        for robot in fleet.robots:
            extra = ("--ros1",) if robot.master is not None else ("--ros2",)
            ships.append(
                ShipProcess(
                    robot_env(robot),
                    collector.url,
                    tmp_path / f"spool-{robot.robot.name}",
                    "--robot",
                    robot.robot.name,
                    *extra,
                )
            )
        for ship in ships:
            ship.wait_for(reading, what="the shipper reading /rosout")
        logged = log_known(fleet, "shipped")
        expected = sum(len(messages) for messages in logged.values())
        assert wait_until(lambda: sum("shipped" in body for body in receiver.bodies()) >= expected, PATIENCE_S)
        for ship in ships:
            ship.wait_for(lambda line: number_after(line, "spooled") == 0 and number_after(line, "sent") >= 4)
    finally:
        codes = [ship.stop() for ship in ships]
        collector.stop()
        receiver.close()
    assert codes == [0, 0, 0]
    arrived = [record for record in receiver.records if "shipped" in record.body]
    assert sorted(record.body for record in arrived) == sorted(m["msg"] for ms in logged.values() for m in ms)
    assert receiver.gzipped  # rotel sends gzip on, as ship sends it
    for record in arrived:
        robot = record.body.split()[1]
        assert record.resource["service.namespace"] == robot
        assert record.resource["host.name"]
    by_body = {record.body: record for record in arrived}
    for messages in logged.values():
        for message in messages:
            record = by_body[message["msg"]]
            if "level_name" in message:  # ROS 1: rospy's node name, its file, function and line
                assert record.resource["service.name"] == "/talker"
                assert (record.severity_number, record.severity_text) == LEVELS[message["level_name"]]
                assert record.attributes["code.file.path"].endswith("rospy_node.py")
                assert record.attributes["code.function.name"] == "read_commands"
                assert record.attributes["code.line.number"] > 0
            else:
                number = {10: 5, 20: 9, 30: 13, 40: 17, 50: 21}[message["level"]]
                assert record.resource["service.name"] == "talker" == record.scope
                assert record.severity_number == number
                assert record.attributes["code.file.path"] == message["file"]
                assert record.attributes["code.function.name"] == message["function"]
                assert record.attributes["code.line.number"] == message["line"]


def test_three_robots_into_chdb_read_back_by_tail(fleet, tmp_path):
    """chDB opens a directory in one process at a time: one shipper reads the three robots
    (the fleet options), and once it has stopped ``tail`` reads the directory."""
    store = tmp_path / "warehouse"
    fleet_options = []
    for robot in fleet.robots:
        if robot.master is None:
            fleet_options += ["--domain", f"{robot.robot.domain}={robot.robot.name}"]
        else:
            fleet_options += ["--master", f"{robot.robot.master}={robot.robot.name}"]
    ship = ShipProcess({**os.environ}, f"chdb://{store}", tmp_path / "spool", *fleet_options)
    try:
        ship.wait_for(lambda line: line.count(" reading /rosout") == 3 and "(0 publishers)" not in line)
        logged = log_known(fleet, "stored")
        expected = sum(len(messages) for messages in logged.values())
        ship.wait_for(lambda line: number_after(line, "sent") >= expected and number_after(line, "spooled") == 0)
    finally:
        assert ship.stop() == 0
    tail = subprocess.run(
        [sys.executable, "-m", "console_tui", "tail", f"chdb://{store}", "--json", "--query", "stored"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert tail.returncode == 0, tail.stderr
    printed = [json.loads(line) for line in tail.stdout.splitlines()]
    assert sorted((p["robot"], p["msg"]) for p in printed) == sorted(
        (name, m["msg"]) for name, messages in logged.items() for m in messages
    )
    stamps = [p["stamp_ns"] for p in printed]
    assert stamps == sorted(stamps)
    by_message = {p["msg"]: p for p in printed}
    for messages in logged.values():
        for message in messages:
            row = by_message[message["msg"]]
            if "level_name" in message:  # ROS 1: rospy's node, its file, function and line
                assert (row["node"], row["function"]) == ("/talker", "read_commands")
                assert row["file"].endswith("rospy_node.py") and row["line"] > 0
                assert row["level"] == {"info": 20, "warn": 30, "error": 40, "fatal": 50}[message["level_name"]]
            else:
                assert row["node"] == "talker" and row["level"] == message["level"]
                assert (row["file"], row["function"], row["line"]) == (
                    message["file"],
                    message["function"],
                    message["line"],
                )
    rows = asyncio.run(rows_in_the_app(f"chdb://{store}", "stored", len(printed)))
    for name, messages in logged.items():
        for message in messages:
            shown = [line for line in rows if message["msg"] in line]
            # its robot in the Robot column, besides the message's own words
            assert len(shown) == 1 and shown[0].count(name) == 2, (message["msg"], rows)


async def rows_in_the_app(address: str, query: str, count: int) -> list[str]:
    """The table's rows under ``query`` once ``count`` show: as ``console-tui chdb://...
    --query QUERY`` makes the app (the Robot column shown, three robots)."""
    source = WarehouseSource(parse_address(address))
    app = ConsoleApp(store=LogStore(), sources=[source], utc=True, query=query)
    async with app.run_test(size=(160, 40)) as pilot:
        await until(
            pilot,
            lambda: len(table_rows(app)) == count,
            what=lambda: f"{count} rows ({len(table_rows(app))} shown)",
        )
        return [line for _, line in table_rows(app).values()]
