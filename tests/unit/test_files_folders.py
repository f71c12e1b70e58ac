"""Folders of logs (issue 19): a ROS 1 run folder, a ROS 2 launch folder and the whole log
directory open as every log in them merged by time; rotated files read as one; the newest
run (``--last``); many files opened only when the merge reaches their time."""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

import pytest

from console_tui.cli import main
from console_tui.model.formats import FormatError
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.files import FileLoad, latest_run, load_records, open_logs
from console_tui.sources.files.merge import merge_by_time

from support.formats import DATA

LOG_DIR = DATA / "ros_log"
RUN_ID = "c0ffee00-d4b2-11eb-9c3e-0242ac110002"
LAUNCH_ID = "2024-10-05-00-46-21-512000-robot-4242"
T0 = 1624512194_000_000_000  # 2021-06-24 05:23:14 UTC


@pytest.fixture(autouse=True)
def utc(monkeypatch):
    """The ROS 1 Python logs' times are local: read them in UTC here."""
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()
    yield
    monkeypatch.undo()
    time.tzset()


@pytest.fixture
def log_dir(tmp_path) -> Path:
    """A copy of the fixture log directory, files dated as the run wrote them."""
    copy = tmp_path / "log"
    shutil.copytree(LOG_DIR, copy, symlinks=True)
    os.utime(copy / RUN_ID / "rosout-1-stdout.log", ns=(T0 + 1_200_000_000, T0 + 1_200_000_000))
    return copy


def _merged(paths):
    opened = open_logs(paths)
    return [r for batch in load_records(opened.files) for r in batch], opened


def test_a_ros1_run_folder_merges_every_log_in_time_order(log_dir):
    records, opened = _merged([log_dir / RUN_ID])
    assert opened.failures == [] and opened.skipped == []
    assert sorted(f.source for f in opened.files) == [
        "master.log",
        "roslaunch-robot-4242.log",
        "rosout-1-stdout.log",
        "rosout.log",
        "talker-2-stdout.log",
        "talker-2.log",
    ]
    traceback = 'failed\nTraceback (most recent call last):\n  File "talker.py", line 18, in main\nZeroDivisionError: division by zero'
    rows = [(r.stamp_ns - T0, r.level, r.node, r.source, r.msg) for r in records]
    assert rows == [
        (
            584_000_000,
            20,
            "roslaunch",
            "roslaunch-robot-4242.log",
            "Checking log directory for disk usage. This may take a while.\nPress Ctrl-C to interrupt",
        ),
        (594_000_000, 20, "roslaunch", "roslaunch-robot-4242.log", "Done checking log file disk usage. Usage is <1GB."),
        (
            595_000_000,
            20,
            "roslaunch",
            "roslaunch-robot-4242.log",
            "roslaunch starting with args ['/opt/ros/noetic/bin/roslaunch', 'demo', 'talker.launch']",
        ),
        (1_010_000_000, 20, "rosmaster.main", "master.log", "initialization complete, waiting for shutdown"),
        (1_011_000_000, 20, "rosmaster.main", "master.log", "Starting ROS Master Node"),
        (
            1_101_000_000,
            20,
            "roslaunch.pmon",
            "roslaunch-robot-4242.log",
            "start_process_monitor: creating ProcessMonitor",
        ),
        (
            1_200_000_000,
            20,
            "/rosout",
            "rosout-1-stdout.log",
            "logging to /home/robot/.ros/log/c0ffee00-d4b2-11eb-9c3e-0242ac110002/rosout.log",
        ),
        (1_200_000_000, 20, "/rosout", "rosout-1-stdout.log", "re-publishing aggregated messages to /rosout_agg"),
        (1_200_000_000, 20, "/rosout", "rosout-1-stdout.log", "subscribed to /rosout"),
        (2_900_000_000, 20, "roslaunch", "roslaunch-robot-4242.log", "process[talker-2]: started with pid [4301]"),
        (2_950_000_000, 20, "rosmaster.master", "master.log", "+PUB [/rosout] /talker http://robot:40123/"),
        (2_950_000_000, 20, "rospy.client", "talker-2.log", "init_node, name[/talker], pid[4301]"),
        (2_990_000_000, 20, "rospy.topics", "talker-2.log", "topicmanager initialized"),
        (3_562_810_000, 20, "/talker", "rosout.log + talker-2.log", "你好，世界: hello 1"),  # in both: one row
        (3_562_810_000, 20, "/talker", "talker-2-stdout.log", "talker starting"),
        (3_562_810_000, 20, "/talker", "talker-2-stdout.log", "你好，世界: hello 1\na line printed after it"),
        # begun in talker-2.log.1, ended in talker-2.log; rosout.log has it too
        (4_100_000_000, 40, "/talker", "rosout.log + talker-2.log", traceback),
        (5_562_810_000, 20, "/talker", "talker-2-stdout.log", "hello 2"),
        (6_990_000_000, 20, "rospy.core", "talker-2.log", "signal_shutdown [atexit]"),
        (7_002_000_000, 30, "roslaunch", "roslaunch-robot-4242.log", "process[talker-2]: required process died"),
    ]
    assert all(not f.problems for f in opened.files)
    chained = next(f for f in opened.files if f.source == "talker-2.log")
    assert chained.title == "ROS 1 Python log, 2 files"


def test_the_whole_log_directory_once_each_under_its_run(log_dir):
    records, _ = _merged([log_dir])
    # The ROS 1 run (two messages in rosout.log and talker-2.log, merged), the launch folder and
    # the node log beside it: one message in both is one row; the other, which a printed line
    # continues in launch.log, is not the same text there, and both stay.
    assert len(records) == 20 + 7
    sources = {r.source for r in records}
    assert f"{RUN_ID}/talker-2.log" in sources and f"{LAUNCH_ID}/launch.log" in sources
    assert "sllidar_node_4245_1728089181700.log" in sources
    assert not any(source.startswith("latest") for source in sources)  # the link is not followed
    assert [r.stamp_ns for r in records] == sorted(r.stamp_ns for r in records)


def test_rotated_files_name_their_own_file_and_line_in_problems(tmp_path):
    run = tmp_path / "run"
    run.mkdir()
    (run / "rosout.log.2").write_bytes(b"1.000000000 INFO /a [a.py:1(f)] [topics: /rosout] one\n")
    (run / "rosout.log.1").write_bytes(
        b"2.000000000 INFO /a [a.py:1(f)] [topics: /rosout] two\nstill two\nnul \x00 here\n"
    )
    (run / "rosout.log").write_bytes(b"3.000000000 INFO /a [a.py:1(f)] [topics: /rosout] three\n")
    (run / "notes.txt").write_text("not a log")
    (run / "empty.log").write_bytes(b"")
    records, opened = _merged([tmp_path / "run"])
    assert [r.msg for r in records] == ["one", "two\nstill two\nnul \x00 here", "three"]
    (problem,) = opened.files[0].problems
    before = len(b"2.000000000 INFO /a [a.py:1(f)] [topics: /rosout] two\nstill two\nnul ")
    assert (problem.source, problem.line, problem.offset) == ("rosout.log.1", 3, before)
    assert "binary data" in problem.what
    assert sorted(p.name for p in opened.skipped) == ["empty.log", "notes.txt"]


def test_a_rotated_part_cut_before_its_last_newline_ends_its_record_there(tmp_path):
    run = tmp_path / "run"
    run.mkdir()
    (run / "rosout.log.1").write_bytes(b"1.000000000 INFO /a [a.py:1(f)] [topics: /rosout] one, cut")
    (run / "rosout.log").write_bytes(b"2.000000000 INFO /a [a.py:1(f)] [topics: /rosout] two\nnul \x00 here\n")
    records, opened = _merged([run])
    assert [r.msg for r in records] == ["one, cut", "two\nnul \x00 here"], "not run together into one record"
    (problem,) = opened.files[0].problems
    assert (problem.source, problem.line) == ("rosout.log", 2), "the line counted in its own file"


def test_an_empty_folder_says_so(tmp_path):
    (tmp_path / "nothing").mkdir()
    (tmp_path / "nothing" / "params.yaml").write_text("a: 1\n")
    opened = open_logs([tmp_path / "nothing"])
    assert opened.files == []
    assert [p.what for p in opened.failures] == ["no log files in this folder (1 other files)"]


def test_a_recording_in_a_folder_is_one_recording(log_dir):
    pytest.importorskip("rosbags")
    from support.formats import hostile_records
    from support.recordings import write_rosbag2

    write_rosbag2(log_dir / RUN_ID / "bag", hostile_records(), storage="mcap")
    opened = open_logs([log_dir / RUN_ID])
    assert "bag" in {f.source for f in opened.files}
    assert not any(f.source.startswith("bag/") for f in opened.files)


def test_the_newest_run_in_the_log_directory(tmp_path, log_dir):
    launch = log_dir / LAUNCH_ID
    os.utime(launch / "launch.log", ns=(1728089183_300_000_000, 1728089183_300_000_000))
    env = {"ROS_LOG_DIR": str(log_dir)}
    assert latest_run(env) == [launch.resolve(), log_dir / "sllidar_node_4245_1728089181700.log"]
    (log_dir / "latest").unlink()
    os.utime(log_dir / RUN_ID, ns=(2_000_000_000_000_000_000, 2_000_000_000_000_000_000))
    assert latest_run(env) == [log_dir / RUN_ID]
    with pytest.raises(FormatError, match="no ROS log directory at"):
        latest_run({"ROS_LOG_DIR": str(tmp_path / "none")})
    (tmp_path / "blank").mkdir()
    with pytest.raises(FormatError, match="no run folders"):
        latest_run({"ROS_LOG_DIR": str(tmp_path / "blank")})


def test_convert_a_folder_and_the_last_run(log_dir, capsys, monkeypatch):
    out = log_dir.parent / "out.jsonl"
    assert main(["convert", str(log_dir / RUN_ID), "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "20 records from 6 files written" in err
    assert "talker-2.log: note: its times are local times without a zone" in err
    monkeypatch.setenv("ROS_LOG_DIR", str(log_dir))
    assert main(["convert", "--last", "-o", str(out)]) == 0
    assert "7 records from 2 files written" in capsys.readouterr().err  # one message in both files: one
    monkeypatch.setenv("ROS_LOG_DIR", str(log_dir / "none"))
    assert main(["convert", "--latest", "-o", str(out)]) == 2
    assert "no ROS log directory at" in capsys.readouterr().err


def test_the_app_is_given_the_last_run():
    from console_tui.cli import add_latest_run, build_parser

    parser = build_parser()
    args = parser.parse_args(["--last", "a.bag"])
    os.environ["ROS_LOG_DIR"] = str(LOG_DIR)
    try:
        add_latest_run(parser, args)
    finally:
        del os.environ["ROS_LOG_DIR"]
    assert args.files[0] == "a.bag" and args.files[1].endswith(LAUNCH_ID)


def test_a_folder_loads_in_the_background_with_its_files_listed(log_dir):
    queue = IntakeQueue()
    load = FileLoad([log_dir / RUN_ID], queue)
    load.start()
    assert load.join(30)
    assert len(queue.drain()) == 20 and load.problems() == []
    assert load.progress.merged == 2  # in rosout.log and talker-2.log
    assert [f.source for f in load.progress.files][:2] == ["master.log", "roslaunch-robot-4242.log"]
    assert set(load.notes()) == {
        "master.log",
        "roslaunch-robot-4242.log",
        "rosout-1-stdout.log",
        "talker-2.log",
        "talker-2-stdout.log",
    }


def test_many_files_are_opened_only_when_their_time_comes(tmp_path):
    folder = tmp_path / "many"
    folder.mkdir()
    for index in range(40):  # forty runs one after the other, a hundred records each
        lines = (f"[INFO] [{index * 1000 + k}.000000000] [n{index}]: m{k}\n" for k in range(100))
        (folder / f"n{index}_1_{1700000000000 + index}.log").write_text("".join(lines))
    opened = open_logs([folder])
    assert all(f.start_hint is not None for f in opened.files)
    most_open = most_started = 0
    stamps = []
    for batch in load_records(opened.files, batch_size=50):
        stamps += [r.stamp_ns for r in batch]
        most_open = max(most_open, _files_open_in(folder))
        if len(stamps) == 50:  # the first batch: only the first file's time has come
            most_started = sum(1 for f in opened.files if f.done > 0)
    assert len(stamps) == 4000 and stamps == sorted(stamps)
    assert most_open <= 2 and most_started <= 2


def _files_open_in(folder: Path) -> int:
    count = 0
    for fd in os.listdir("/proc/self/fd"):
        try:
            count += os.readlink(f"/proc/self/fd/{fd}").startswith(str(folder))
        except OSError:
            pass  # the descriptor listing the folder itself, closed already
    return count


def test_the_merge_starts_a_stream_when_its_time_comes():
    from console_tui.model.store.record import LogRecord

    started: list[int] = []

    def stream(index: int, stamps: list[int]):
        started.append(index)
        yield [LogRecord(s, 20, f"s{index}", "m") for s in stamps]

    streams = [stream(0, [10, 20]), stream(1, [30, 40]), stream(2, [5, 50])]
    merged = merge_by_time(streams, starts=[10, 30, None], batch_size=1)
    order = []
    for batch in merged:
        order += [(r.stamp_ns, r.node) for r in batch]
        if batch[0].stamp_ns == 20:
            assert started == [2, 0]  # the stream of time 30 is not touched yet
    assert order == [(5, "s2"), (10, "s0"), (20, "s0"), (30, "s1"), (40, "s1"), (50, "s2")]
