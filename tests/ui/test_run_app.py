"""``console-tui`` run in this process, from the command line to the exit code: files only,
rclpy missing, a query at start, sources that fail to start or stop. Live ROS 2 runs are in
tests/ros/test_run_app_live.py."""

from __future__ import annotations

import sys
import threading

import pytest

from console_tui.model.formats.save import save_records

from support.feed import records
from support.run_main import run_main
from support.ui import line_with, screen_text, until


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


@pytest.fixture
def no_ros(monkeypatch):
    """This Python without rclpy, and no ROS 1 in the environment."""
    monkeypatch.setitem(sys.modules, "rclpy", None)
    for name in ("ROS_MASTER_URI", "ROS_VERSION"):
        monkeypatch.delenv(name, raising=False)


def intake_threads() -> list[str]:
    return [t.name for t in threading.enumerate() if "intake" in t.name]


def test_files_only_show_their_records_start_no_ros_and_exit_0(tmp_path, monkeypatch, no_ros):
    path = tmp_path / "saved.jsonl"
    save_records(records(40), path, "jsonl")
    during: dict[str, object] = {}

    async def script(pilot) -> None:
        await until(pilot, lambda: "40/40 shown" in screen_text(pilot.app), what="the file's records")
        line_with(pilot.app, "is divisible by 20")
        during["intake"] = intake_threads()
        during["status"] = screen_text(pilot.app).splitlines()[-2]
        await pilot.press("q")

    code, apps = run_main(monkeypatch, [str(path), "--utc"], script)
    assert code == 0 and len(apps) == 1
    assert during["intake"] == [], "files only: no live source"
    assert "/rosout " not in str(during["status"]) and "pubs" not in str(during["status"])


def test_start_up_runs_without_garbage_collections_until_after_the_first_frame(tmp_path, monkeypatch, no_ros):
    """The collector is off from the command line to the app's first frame; then the app
    collects once (its ``CollectionPolicy``) and it is on again, also after the run."""
    import gc

    from console_tui.ui.gc_policy import CollectionPolicy

    path = tmp_path / "saved.jsonl"
    save_records(records(5), path, "jsonl")
    seen: dict[str, object] = {}
    start = CollectionPolicy.start

    def watched_start(policy: CollectionPolicy) -> None:
        seen["on before"] = gc.isenabled()
        start(policy)
        seen["on after"] = gc.isenabled()

    monkeypatch.setattr(CollectionPolicy, "start", watched_start)

    async def script(pilot) -> None:
        await until(pilot, lambda: "5/5 shown" in screen_text(pilot.app), what="the file's records")
        await until(pilot, lambda: "on after" in seen, what="the collection after the first frame")
        await pilot.press("q")

    try:
        code, _apps = run_main(monkeypatch, [str(path)], script)
        assert code == 0
        assert seen["on before"] is False, "collections during start-up"
        assert seen["on after"] is True and gc.isenabled()
    finally:
        gc.enable()


def test_without_rclpy_exit_2_with_what_to_do_and_no_app(monkeypatch, capsys, no_ros):
    async def script(pilot) -> None:  # never runs: the app is not started
        raise AssertionError("the app started")

    code, apps = run_main(monkeypatch, [], script)
    assert code == 2 and apps == []
    err = capsys.readouterr().err
    assert err.startswith("console-tui: ROS 2 (rclpy) is not available in this Python (")
    assert "pip install 'console-tui[ros]'" in err and "console-tui --ros1" in err
    assert "Traceback" not in err


def test_with_files_and_live_but_no_rclpy_exit_2(tmp_path, monkeypatch, capsys, no_ros):
    path = tmp_path / "saved.csv"
    save_records(records(5), path, "rqt")

    async def script(pilot) -> None:
        raise AssertionError("the app started")

    code, apps = run_main(monkeypatch, ["--live", str(path)], script)
    assert code == 2 and apps == [] and "rclpy" in capsys.readouterr().err


def test_a_query_and_rules_given_at_start_are_in_force(tmp_path, monkeypatch, no_ros):
    path = tmp_path / "saved.jsonl"
    save_records(records(100), path, "jsonl")
    rules = tmp_path / "rules.toml"
    rules.write_text('[[rules]]\nrole = "exclude"\nkind = "node"\nnames = ["count_and_log"]\n')
    seen: dict[str, str] = {}

    async def script(pilot) -> None:
        await until(pilot, lambda: "/100 shown" in screen_text(pilot.app), what="the file's records")
        seen["screen"] = screen_text(pilot.app)
        await pilot.press("q")

    code, _ = run_main(monkeypatch, [str(path), "--utc", "--query", "level>=error", "--rules", str(rules)], script)
    assert code == 0
    # 100 records: 10 ERROR (all from count_and_log, which the rules file hides), 10 FATAL.
    assert "10/100 shown" in seen["screen"]
    table = [line for line in seen["screen"].splitlines() if line.split()[:1] and line.split()[0].isdigit()]
    assert table and all(("ERROR" in line or "FATAL" in line) and "count_and_log" not in line for line in table)


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--query", "level>=loud"], "--query is not valid"),
        (["--rules", "/no/such/rules.toml"], "--rules:"),
        (["--max-messages", "0"], "--max-messages"),
    ],
)
def test_bad_arguments_exit_2_before_the_app(monkeypatch, capsys, argv, message):
    async def script(pilot) -> None:
        raise AssertionError("the app started")

    with pytest.raises(SystemExit) as exit_:
        run_main(monkeypatch, argv, script)
    assert exit_.value.code == 2 and message in capsys.readouterr().err
