"""``console-tui`` run in this process with real ROS 2 nodes: the live source and the logger
control wired up, the demo nodes started and ended with the app, everything stopped at exit."""

from __future__ import annotations

import asyncio
import threading

import pytest
from conftest import next_domain_id

from support.rosproc import pid_alive, wait_until
from support.run_main import run_main
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
    assert apps[0].main.sources == []


def test_the_live_intake_starts_before_the_app_is_made_and_stops_if_it_cannot_be(ros_env, monkeypatch):
    """The intake process starts before the app's UI is imported, so that its start-up runs
    beside the app's (the first live row comes sooner); when the app then cannot be made,
    that process is stopped, not left behind."""
    from console_tui.cli import main
    from console_tui.ui.app import ConsoleApp

    before = console_threads()
    started: list[list[bool]] = []

    def cannot_be_made(self, *args, **kwargs) -> None:
        started.append([source.started for source in kwargs["sources"]])
        assert wait_until(lambda: all(source.pid is not None for source in kwargs["sources"]))
        raise RuntimeError("the app could not be made")

    monkeypatch.setattr(ConsoleApp, "__init__", cannot_be_made)
    with pytest.raises(RuntimeError, match="could not be made"):
        main(["--topic", "/rosout"])
    assert started == [[True]]
    assert wait_until(lambda: console_threads() == before), console_threads()


def test_demo_starts_its_nodes_and_they_end_with_the_app(ros_env, monkeypatch):
    pids: list[int] = []

    async def script(pilot) -> None:
        app = pilot.app
        await until(pilot, lambda: "demo: 4 nodes" in screen_text(app), timeout=30, what="the demo nodes")
        await until(pilot, lambda: "count_and_log" in screen_text(app), timeout=30, what="a demo message")
        pids.extend(p.pid for source in app.main.sources for p in getattr(source, "processes", []))
        await asyncio.sleep(0)
        await pilot.press("q")

    domain = str(next_domain_id())  # within the tests' domains
    code, _ = run_main(monkeypatch, ["--demo", "--demo-domain", domain, "--utc"], script, size=(140, 30))
    assert code == 0 and len(pids) == 4
    assert wait_until(lambda: not any(pid_alive(pid) for pid in pids))


def test_the_demo_stays_out_of_the_users_graph(nodes, ros_env, ros_runtime, monkeypatch):
    """A second console on the user's domain, running all along, sees the user's own node and
    none of the demo's messages, which run on a domain of their own (shown in the status line)."""
    from test_cli_tail_live import subscribed

    from support.tail_process import TailProcess

    user_domain = ros_env["ROS_DOMAIN_ID"]
    demo_domain = str(next_domain_id())
    assert demo_domain != user_domain
    second = TailProcess(ros_env, "--topic", "/rosout", "--format", "{name}: {message}")
    seen: dict[str, str] = {}
    try:
        probe = ros_runtime.create_node("probe")
        assert wait_until(lambda: subscribed(probe, 1), 60), "the second console never subscribed"

        async def script(pilot) -> None:
            app = pilot.app
            await until(pilot, lambda: "count_and_log" in screen_text(app), timeout=60, what="a demo message")
            await until(pilot, lambda: "navigation.planner" in screen_text(app), timeout=60, what="the planner")
            seen["status"] = screen_text(app).splitlines()[-2]
            await pilot.press("q")

        code, _ = run_main(monkeypatch, ["--demo", "--demo-domain", demo_domain, "--utc"], script, size=(200, 30))
        assert code == 0
        # The user's own node on the user's domain: the second console hears it, and only it.
        talker = nodes.start("talker.py", "--name", "users_own")
        talker.expect("ready")
        talker.send({"cmd": "log", "level": "info", "msg": "the user's own message"})
        lines = second.take_text(1, timeout=60)
    finally:
        second.stop()
    assert lines == ["users_own: the user's own message"], lines
    assert f"domain {demo_domain}" in seen["status"] and f"domain {user_domain}" not in seen["status"], seen


def test_a_silent_ros1_master_uri_is_said_in_the_status_line(ros_env, monkeypatch):
    """ROS_MASTER_URI set, nothing there: ROS 2 is read, and the status line says why."""
    from support.ros1 import own_port

    uri = f"http://127.0.0.1:{own_port()}/"
    monkeypatch.setenv("ROS_MASTER_URI", uri)
    seen: dict[str, str] = {}

    async def script(pilot) -> None:
        app = pilot.app
        await until(pilot, lambda: "ROS 2 domain" in screen_text(app), timeout=30, what="the live source")
        seen["screen"] = screen_text(app)
        await pilot.press("q")

    code, _ = run_main(monkeypatch, ["--utc"], script, size=(200, 30))
    assert code == 0
    status = seen["screen"].splitlines()[-2]
    assert f"no ROS 1 master answered at {uri} (--ros1 waits for it)" in status, status
