"""``console-tui`` run in this process with real ROS 2 nodes: the live source and the logger
control wired up, the demo nodes started and ended with the app, everything stopped at exit."""

from __future__ import annotations

import asyncio
import threading

import pytest

from support.launch import run_main
from support.rosproc import pid_alive, wait_until
from support.ui import line_with, screen_text, until

pytestmark = pytest.mark.ros2


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    for name in ("ROS_MASTER_URI", "ROS_VERSION"):
        monkeypatch.delenv(name, raising=False)


def console_threads() -> list[str]:
    return [t.name for t in threading.enumerate() if t.name.startswith("console-tui")]


def test_live_topic_shows_a_nodes_messages_and_exit_stops_everything(nodes, monkeypatch):
    talker = nodes.start("talker.py", "--name", "launch_talker")
    talker.expect("ready")
    before = console_threads()
    seen: dict[str, object] = {}

    async def script(pilot) -> None:
        app = pilot.app
        await until(pilot, lambda: "/rosout 1 pub " in screen_text(app), what="the talker on /rosout")
        talker.send({"cmd": "log", "level": "error", "msg": "seen through the launch"})
        await until(pilot, lambda: "seen through the launch" in screen_text(app), what="the message on screen")
        seen["row"] = line_with(app, "seen through the launch")[1]
        seen["status"] = screen_text(app).splitlines()[-2]
        seen["threads"] = console_threads()
        await pilot.press("q")

    code, apps = run_main(monkeypatch, ["--topic", "/rosout", "--utc"], script, size=(140, 30))
    assert code == 0
    assert "ERROR" in seen["row"] and "launch_talker" in seen["row"] and "talker.py" in seen["row"]
    assert "ROS 2 domain" in str(seen["status"]), seen["status"]
    assert len(seen["threads"]) > len(before), "the intake (and logger) threads ran"
    assert wait_until(lambda: console_threads() == before), console_threads()
    assert apps[0].sources == []


def test_demo_starts_its_nodes_and_they_end_with_the_app(ros_env, monkeypatch):
    pids: list[int] = []

    async def script(pilot) -> None:
        app = pilot.app
        await until(pilot, lambda: "demo: 4 nodes" in screen_text(app), timeout=30, what="the demo nodes")
        await until(pilot, lambda: "count_and_log" in screen_text(app), timeout=30, what="a demo message")
        pids.extend(p.pid for source in app.sources for p in getattr(source, "processes", []))
        await asyncio.sleep(0)
        await pilot.press("q")

    code, _ = run_main(monkeypatch, ["--demo", "--utc"], script, size=(140, 30))
    assert code == 0 and len(pids) == 4
    assert wait_until(lambda: not any(pid_alive(pid) for pid in pids))
