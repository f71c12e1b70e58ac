"""ROS 1 files made by the real tools: a bag from Debian's 'rosbag record' and the
rosout.log of a real roscore, with a rospy node logging."""

from __future__ import annotations

import json
import subprocess

import pytest

from console_tui.cli import main as cli_main
from console_tui.sources.files import load_records, open_log_file, open_logs
from console_tui.sources.files.repeats import RepeatMerger

from support.formats import fields
from support.ros1 import SYSTEM_PYTHON, Ros1Master, own_port, ros1_environment, ros1_missing, stop_group
from support.rosproc import NODES

pytestmark = pytest.mark.ros1


@pytest.fixture(scope="module")
def ros1_run(tmp_path_factory):
    """roscore + 'rosbag record -a' + a rospy node that logs; returns the bag, the
    rosout.log and what the node says it logged."""
    reason = ros1_missing("rosbag")
    if reason:
        pytest.skip(reason)
    base = tmp_path_factory.mktemp("ros1")
    port = own_port()
    env = ros1_environment(base, port)
    bag = base / "run.bag"
    master = Ros1Master(base, port, env)
    recorder = None
    try:
        master.start()
        recorder = subprocess.Popen(
            ["rosbag", "record", "-a", "-O", str(bag), "__name:=recorder"],
            env=env,
            start_new_session=True,
            stdout=open(base / "record.out", "wb"),
            stderr=subprocess.STDOUT,
        )
        talker = subprocess.run(
            [SYSTEM_PYTHON, str(NODES / "ros1_talker.py")], env=env, capture_output=True, text=True, timeout=90
        )
        assert talker.returncode == 0, talker.stdout + talker.stderr
        logged = next(json.loads(line) for line in talker.stdout.splitlines() if '"logged"' in line)["messages"]
    finally:
        if recorder is not None:
            stop_group(recorder, timeout=20)
        master.stop()
    assert bag.exists(), (base / "record.out").read_text()
    [rosout_log] = [p for p in (base / "log").glob("*/rosout.log") if p.parent.name != "latest"]
    return {"bag": bag, "rosout_log": rosout_log, "logged": logged}


def _records(path) -> tuple[list, object]:
    log_file = open_log_file(path)
    return [r for batch in log_file.batches() for r in batch], log_file


def _matches(records, logged) -> None:
    ours = [r for r in records if r.file == "ros1_talker.py"]  # rospy logs its own DEBUG too
    assert [(r.level, r.msg, r.file, r.function, r.line) for r in ours] == [
        ({1: 10, 2: 20, 4: 30, 8: 40, 16: 50}[m["level"]], m["msg"], m["file"], m["function"], m["line"])
        for m in logged
    ]


def test_bag_recorded_by_rosbag(ros1_run):
    records, log_file = _records(ros1_run["bag"])
    assert log_file.kind == "ros1-bag" and list(log_file.problems) == []
    assert log_file.topics == ["/rosout_agg"]  # /rosout was recorded too; not read twice
    _matches(records, ros1_run["logged"])
    assert {r.source for r in records} == {"run.bag"}


def test_rosout_log_of_roscore(ros1_run):
    records, log_file = _records(ros1_run["rosout_log"])
    assert log_file.kind == "rosout" and list(log_file.problems) == []
    _matches(records, ros1_run["logged"])


def test_bag_and_rosout_log_agree(ros1_run):
    from_bag, _ = _records(ros1_run["bag"])
    from_log, _ = _records(ros1_run["rosout_log"])
    # rospy's own DEBUG messages from before 'rosbag record' subscribed are only in rosout.log.
    ours = [[fields(r)[:7] for r in records if r.file == "ros1_talker.py"] for records in (from_bag, from_log)]
    assert ours[0] == ours[1] and len(ours[0]) == len(ros1_run["logged"])


def test_convert_merges_both(ros1_run, tmp_path, capsys):
    out = tmp_path / "both.jsonl"
    assert cli_main(["convert", str(ros1_run["bag"]), str(ros1_run["rosout_log"]), "-o", str(out)]) == 0
    lines = [json.loads(line) for line in out.read_text().splitlines()]
    assert sum(1 for line in lines if line["file"] == "ros1_talker.py") == 2 * len(ros1_run["logged"])
    assert {line["source"] for line in lines} == {"run.bag", "rosout.log"}
    stamps = [line["stamp_ns"] for line in lines]
    assert stamps == sorted(stamps)


def test_the_log_folder_opened_whole_shows_each_message_once(ros1_run):
    """rosout.log and the node's own log file (rospy's, in the log directory: the node was not
    launched by roslaunch) both hold its messages: one row each."""
    folder = ros1_run["rosout_log"].parent.parent
    opened = open_logs([folder])
    kinds = {f.source: f.kind for f in opened.files}
    repeats = RepeatMerger()
    records = [r for batch in load_records(opened.files, repeats=repeats) for r in batch]
    texts = [m["msg"] for m in ros1_run["logged"]]
    ours = [r for r in records if r.msg in texts]
    assert sorted(r.msg for r in ours) == sorted(texts), kinds
    assert repeats.merged >= len(texts), kinds
    assert all(r.file == "ros1_talker.py" and " + " in r.source for r in ours), kinds
