"""``console-tui clean``: where the log directory is, sizes, and what purge removes (and never)."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest

from console_tui.cli import main
from console_tui.ros.log_dir import LogRun, UnsafeRemoval, remove_run, ros_log_dir, scan_runs

DAY = 86400.0


def test_log_dir_from_the_environment():
    assert ros_log_dir({"HOME": "/h"}) == Path("/h/.ros/log")
    assert ros_log_dir({"HOME": "/h", "ROS_HOME": "/r"}) == Path("/r/log")
    assert ros_log_dir({"HOME": "/h", "ROS_HOME": "~/ros"}) == Path("/h/ros/log")
    assert ros_log_dir({"HOME": "/h", "ROS_HOME": "/r", "ROS_LOG_DIR": "~/logs"}) == Path("/h/logs")
    assert ros_log_dir({"HOME": "/h", "ROS_LOG_DIR": ""}) == Path("/h/.ros/log")


def make_file(path: Path, size: int, age_days: float) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"x" * size)
    moment = time.time() - age_days * DAY
    os.utime(path, (moment, moment))


def age(path: Path, age_days: float) -> None:
    moment = time.time() - age_days * DAY
    os.utime(path, (moment, moment), follow_symlinks=False)


@pytest.fixture
def tree(tmp_path):
    """A log directory with ROS 1 runs, a launch directory, node logs, symlinks in and out,
    and an outside directory that must survive everything."""
    outside = tmp_path / "outside"
    make_file(outside / "precious.log", 5000, 30)
    log = tmp_path / "log"
    ros1_old = log / "0b8c1f2e-1111-2222-3333-444455556666"
    make_file(ros1_old / "rosout.log", 4000, 20)
    make_file(ros1_old / "talker-1.log", 1000, 20)
    age(ros1_old, 20)
    ros1_new = log / "9f9e8d7c-1111-2222-3333-444455556666"
    make_file(ros1_new / "rosout.log", 3000, 2)
    age(ros1_new, 2)
    launch = log / "2026-11-10-10-00-00-123456-robot-4242"
    make_file(launch / "launch.log", 2000, 10)
    (launch / "escape").symlink_to(outside)  # inside a run: removed as a link only
    age(launch / "escape", 10)
    age(launch, 10)
    make_file(log / "talker_1234_1700000000000.log", 500, 8)
    make_file(log / "listener_99_1700000000001.log", 100, 0.5)
    (log / "latest").symlink_to(ros1_new)
    (log / "out").symlink_to(outside)
    return log, outside


def test_scan_sizes_kinds_and_times(tree):
    log, _ = tree
    runs = {run.name: run for run in scan_runs(log)}
    assert runs["0b8c1f2e-1111-2222-3333-444455556666"].size == 5000
    assert runs["0b8c1f2e-1111-2222-3333-444455556666"].kind == "ROS 1 run"
    assert runs["2026-11-10-10-00-00-123456-robot-4242"].size == 2000  # the symlink to outside counts 0
    assert runs["2026-11-10-10-00-00-123456-robot-4242"].kind == "ros2 launch"
    assert runs["talker_1234_1700000000000.log"].kind == "ROS 2 node log"
    assert runs["out"].type == runs["latest"].type == "symlink" and runs["out"].size == 0
    assert sum(run.size for run in runs.values()) == 5000 + 3000 + 2000 + 500 + 100


def test_check_prints_total_and_largest(tree, capsys):
    log, _ = tree
    assert main(["clean", "check", "--dir", str(log), "--top", "2"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == f"{log}: 10K in 5 runs"  # the latest link is no run
    assert out[1] == "Also 1 entry that is not a ROS log (out): never removed."
    assert out[2] == "Largest runs:"
    assert "4.9K" in out[3] and out[3].endswith("0b8c1f2e-1111-2222-3333-444455556666")
    assert "2.9K" in out[4] and "ROS 1 run" in out[4] and len(out) == 5


def names(log: Path) -> set[str]:
    return {entry.name for entry in log.iterdir()}


@pytest.mark.parametrize(
    ("options", "kept", "removed"),
    [
        pytest.param(
            ["--older-than", "7d"],
            {"9f9e8d7c-1111-2222-3333-444455556666", "listener_99_1700000000001.log", "latest", "out"},
            "3 runs",
            id="older-than",
        ),
        # 10,600 bytes: the 20-day run (5000), then the 10-day launch (2000) go; 3,600 are left.
        pytest.param(
            ["--keep-size", "4K"],
            {
                "9f9e8d7c-1111-2222-3333-444455556666",
                "talker_1234_1700000000000.log",
                "listener_99_1700000000001.log",
                "latest",
                "out",
            },
            "2 runs",
            id="keep-size-removes-the-oldest-first",
        ),
    ],
)
def test_purge_by_age_and_by_size(tree, capsys, options, kept, removed):
    log, outside = tree
    assert main(["clean", "purge", "--dir", str(log), *options, "--yes", "--force"]) == 0
    assert names(log) == kept
    assert (outside / "precious.log").stat().st_size == 5000
    assert f"Removed {removed}" in capsys.readouterr().out


def test_purge_all_removes_ros_logs_and_links_never_their_targets(tree):
    log, outside = tree
    assert main(["clean", "purge", "--dir", str(log), "--yes", "--force"]) == 0
    assert names(log) == {"out"}  # not a ROS log: left alone
    assert sorted(p.name for p in outside.iterdir()) == ["precious.log"]


def test_purge_removing_the_latest_run_removes_the_dangling_latest_link(tree):
    log, _ = tree
    assert main(["clean", "purge", "--dir", str(log), "--older-than", "1d", "--yes", "--force"]) == 0
    assert names(log) == {"listener_99_1700000000001.log", "out"}


def test_purge_asks_and_refuses_without_a_terminal(tree, capsys, monkeypatch):
    log, _ = tree
    before = names(log)
    monkeypatch.setattr("sys.stdin", open(os.devnull))
    assert main(["clean", "purge", "--dir", str(log), "--force"]) == 3
    assert names(log) == before
    assert "pass --yes" in capsys.readouterr().err


def test_purge_with_nothing_to_do_and_no_directory(tmp_path, capsys):
    assert main(["clean", "purge", "--dir", str(tmp_path / "none"), "--yes"]) == 0
    assert main(["clean", "check", "--dir", str(tmp_path / "none")]) == 0
    assert "no log directory" in capsys.readouterr().out


def test_bad_arguments_exit_2(tree):
    log, _ = tree
    for argv in (["--older-than", "soon"], ["--keep-size", "lots"]):
        with pytest.raises(SystemExit) as exit_info:
            main(["clean", "purge", "--dir", str(log), "--yes", *argv])
        assert exit_info.value.code == 2


def test_remove_run_refuses_names_that_leave_the_directory(tree):
    log, outside = tree
    for name in ("..", "../outside", "a/b", ""):
        with pytest.raises(UnsafeRemoval):
            remove_run(log, LogRun(name, "directory", 0, 0.0, 0))
    # A run scanned as a directory that became a symlink to outside: left alone.
    (log / "swapped").symlink_to(outside)
    with pytest.raises(UnsafeRemoval):
        remove_run(log, LogRun("swapped", "directory", 0, 0.0, 0))
    assert (outside / "precious.log").exists()
