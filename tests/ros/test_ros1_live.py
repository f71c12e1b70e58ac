"""The native ROS 1 live source against Debian's real ROS 1: roscore (or a bare rosmaster),
rospy nodes, a roscpp node built here; faults as they happen on robots."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import time

import pytest

from console_tui.sources.log_topics import ROSOUT, ROSOUT_AGG

from support.ros1 import kill_group
from support.ros1_source import Collected

pytestmark = pytest.mark.ros1

ROSOUT_NODE = shutil.which("rosout") or "/usr/lib/rosout/rosout"
LEVELS = {"debug": 10, "info": 20, "warn": 30, "error": 40, "fatal": 50}


def _levels_of(records, node: str) -> set[int]:
    return {r.level for r in records if r.node == node}


def test_rosout_agg_from_rospy_and_roscpp_nodes_every_severity(roscore, ros1_nodes, roscpp_binary):
    ros1_nodes.rospy("rospy_node.py", "py_talker", "--period", "0.1", "--debug").expect("ready")
    ros1_nodes.roscpp("talk", "cpp_talker", "100").expect("ready")
    with Collected() as got:
        got.wait(lambda c: c.status.topic == ROSOUT_AGG and c.status.publishers == 1, what="/rosout_agg")
        got.wait(lambda c: _levels_of(c.records, "/py_talker") == set(LEVELS.values()), what="rospy severities")
        got.wait(lambda c: {20, 30, 40, 50} <= _levels_of(c.records, "/cpp_talker"), what="roscpp severities")
        assert got.status.problem == "" and got.status.lost == 0
        assert got.status.origin == f"ROS 1 {roscore.uri}"
    py = next(r for r in got.records if r.node == "/py_talker" and r.msg.startswith("warn "))
    assert (py.level, py.file, py.function, py.source) == (30, "rospy_node.py", "main", ROSOUT_AGG)
    assert py.line > 0 and py.stamp_ns > 1_600_000_000 * 10**9
    assert py.topics == "/rosout"
    cpp = next(r for r in got.records if r.node == "/cpp_talker" and r.msg.startswith("error "))
    assert cpp.file.endswith("roscpp_node.cpp") and cpp.function == "talk" and cpp.line > 0
    assert abs(cpp.stamp_ns - time.time_ns()) < 60 * 10**9


def test_rosout_directly_when_no_rosout_node_runs(bare_master, ros1_nodes):
    ros1_nodes.rospy("rospy_node.py", "alpha", "--period", "0.1").expect("ready")
    ros1_nodes.rospy("rospy_node.py", "beta", "--period", "0.1").expect("ready")
    with Collected() as got:
        got.wait(lambda c: c.status.topic == ROSOUT and c.status.publishers == 2, what="/rosout from both")
        got.wait_for("/alpha", "error ")
        got.wait_for("/beta", "fatal ")
    assert {r.source for r in got.records} == {ROSOUT}
    keys = [(r.stamp_ns, r.node, r.msg) for r in got.records]
    assert len(keys) == len(set(keys))  # latched first messages not repeated


def test_publisher_started_after_the_console(roscore, ros1_nodes):
    with Collected() as got:
        got.wait(lambda c: c.status.topic == ROSOUT_AGG, what="/rosout_agg")
        time.sleep(0.5)
        ros1_nodes.rospy("rospy_node.py", "late", "--period", "0.1").expect("ready")
        got.wait_for("/late", "warn ")


def test_bare_master_then_rosout_node_appears_moves_to_rosout_agg(bare_master, ros1_nodes, ros1_env, tmp_path):
    node = ros1_nodes.rospy("rospy_node.py", "steady", "--period", "0.05")
    node.expect("ready")
    with Collected() as got:
        got.wait(lambda c: c.status.topic == ROSOUT and c.status.publishers == 1, what="/rosout")
        rosout = _start_rosout(ros1_env, tmp_path)
        try:
            got.wait(lambda c: c.status.topic == ROSOUT_AGG and c.status.publishers == 1, what="/rosout_agg")
            count = len(got.records)
            got.wait(lambda c: len(c.records) > count + 20 and c.records[-1].source == ROSOUT_AGG, what="agg rows")
            got.wait(lambda c: c.source.node_name not in bare_master.subscribers(ROSOUT), what="/rosout left")
        finally:
            kill_group(rosout)
    ours = [r for r in got.records if r.node == "/steady"]
    counts = {}
    for record in ours:
        counts[record.msg] = counts.get(record.msg, 0) + 1
    assert max(counts.values()) == 1, "a message came twice while moving between topics"
    numbers = sorted({int(r.msg.split()[1]) for r in ours if r.msg.startswith("info ")})
    assert numbers == list(range(numbers[0], numbers[-1] + 1)), "a message was lost while moving between topics"


def _start_rosout(env, tmp_path) -> subprocess.Popen:
    return subprocess.Popen(
        [ROSOUT_NODE, "__name:=rosout"],
        env=env,
        start_new_session=True,
        stdout=open(tmp_path / "rosout.out", "ab"),
        stderr=subprocess.STDOUT,
    )


def _survivor_rows(collected) -> int:
    return len([r for r in collected.records if r.node == "/survivor"])


def test_killed_rosout_node_stays_registered_and_nodes_are_read_directly(bare_master, ros1_nodes, ros1_env, tmp_path):
    rosout = _start_rosout(ros1_env, tmp_path)
    try:
        ros1_nodes.rospy("rospy_node.py", "survivor", "--period", "0.1").expect("ready")
        with Collected() as got:
            got.wait(lambda c: c.status.topic == ROSOUT_AGG and c.status.publishers == 1, what="/rosout_agg")
            got.wait_for("/survivor", "info ")
            kill_group(rosout)
            assert "/rosout" in bare_master.publishers(ROSOUT_AGG)  # a stale registration
            got.wait(lambda c: c.status.topic == ROSOUT and c.status.publishers == 1, what="/rosout directly")
            count = _survivor_rows(got)
            got.wait(lambda c: _survivor_rows(c) > count + 10, what="more rows")
            assert got.status.problem == ""
    finally:
        kill_group(rosout)
    keys = [(r.stamp_ns, r.node, r.msg) for r in got.records]
    assert len(keys) == len(set(keys))


def test_rosout_node_respawned_by_roscore_is_followed(roscore, ros1_nodes):
    ros1_nodes.rospy("rospy_node.py", "survivor", "--period", "0.1").expect("ready")
    with Collected() as got:
        got.wait(lambda c: c.status.topic == ROSOUT_AGG and c.status.publishers == 1, what="/rosout_agg")
        got.wait_for("/survivor", "info ")
        old = roscore.node_pid("/rosout")
        os.kill(old, signal.SIGKILL)
        got.wait(lambda c: roscore.node_pid("/rosout") not in (None, old), what="roscore to start rosout again")
        count = _survivor_rows(got)
        got.wait(lambda c: _survivor_rows(c) > count + 10, timeout=30, what="rows through the new rosout node")
        assert got.status.topic == ROSOUT_AGG and got.status.publishers == 1 and got.status.problem == ""


def test_master_restarted_mid_run(roscore, ros1_nodes):
    ros1_nodes.rospy("rospy_node.py", "before", "--period", "0.1").expect("ready")
    with Collected() as got:
        got.wait_for("/before", "info ")
        roscore.restart()
        ros1_nodes.rospy("rospy_node.py", "after", "--period", "0.1").expect("ready")
        got.wait_for("/after", "info ")
        # registered again with the new master, under the same name, on /rosout_agg once the
        # restarted rosout node publishes it again (until then it may read /rosout directly)
        got.wait(
            lambda c: c.status.topic == ROSOUT_AGG and c.source.node_name in roscore.subscribers(ROSOUT_AGG),
            timeout=30,
            what="the console registered again on /rosout_agg",
        )
        assert got.source.master_restarts >= 1  # the master's going and coming may be seen in two steps
        assert got.status.problem == ""


def test_master_unreachable_then_started(tmp_path, ros1_env, ros1_nodes):
    from support.ros1 import Ros1Master

    port = int(ros1_env["ROS_MASTER_URI"].rsplit(":", 1)[1])
    with Collected() as got:
        got.wait(lambda c: "waiting for master at" in c.status.problem, what="the waiting line")
        time.sleep(1.5)  # it keeps trying
        assert got.status.running and ros1_env["ROS_MASTER_URI"] in got.status.problem
        master = Ros1Master(tmp_path, port, ros1_env)
        master.start()
        try:
            ros1_nodes.rospy("rospy_node.py", "finally", "--period", "0.1").expect("ready")
            got.wait_for("/finally", "info ")
            assert got.status.problem == ""
        finally:
            ros1_nodes.stop_all()
            master.stop()


def test_rosnode_info_ping_and_kill_treat_the_console_as_a_node(roscore, ros1_nodes, ros1_env):
    ros1_nodes.rospy("rospy_node.py", "talker", "--period", "0.1").expect("ready")
    with Collected() as got:
        got.wait(lambda c: c.status.publishers == 1, what="a connection")
        name = got.source.node_name
        info = subprocess.run(["rosnode", "info", name], env=ros1_env, capture_output=True, text=True, timeout=30)
        assert info.returncode == 0, info.stderr
        assert f"Node [{name}]" in info.stdout
        assert f" * {ROSOUT_AGG} [rosgraph_msgs/Log]" in info.stdout
        assert "direction: inbound" in info.stdout and "to: /rosout" in info.stdout
        ping = subprocess.run(
            ["rosnode", "ping", "-c", "2", name], env=ros1_env, capture_output=True, text=True, timeout=30
        )
        assert ping.returncode == 0 and "xmlrpc reply from" in ping.stdout, ping.stdout + ping.stderr
        kill = subprocess.run(["rosnode", "kill", name], env=ros1_env, capture_output=True, text=True, timeout=30)
        assert kill.returncode == 0, kill.stdout + kill.stderr
        got.wait(lambda c: not c.status.running, what="the source to stop")
        assert "stopped by" in got.status.problem
    listed = subprocess.run(["rosnode", "list"], env=ros1_env, capture_output=True, text=True, timeout=30).stdout
    assert name not in listed


def test_unregisters_on_stop(roscore):
    with Collected() as got:
        got.wait(lambda c: c.status.topic == ROSOUT_AGG, what="registration")
        name = got.source.node_name
        got.wait(lambda c: name in roscore.subscribers(ROSOUT_AGG), what="the subscription registered")
    assert name not in roscore.subscribers(ROSOUT_AGG)


def test_a_publisher_of_another_type_is_reported(roscore, ros1_nodes):
    ros1_nodes.rospy("rospy_node.py", "chatty", "--period", "0", "--publish", "/chatter").expect("ready")
    with Collected(topic="/chatter") as got:
        got.wait(lambda c: "refused /chatter" in c.status.problem, what="the refusal")
        assert "md5sum" in got.status.problem or "type" in got.status.problem
        assert got.status.publishers == 0 and got.status.running


async def test_files_and_live_ros1_in_one_timeline(roscore, ros1_nodes, tmp_path):
    """--live with files, on ROS 1: the recording comes first, the live rows follow in time order."""
    pytest.importorskip("rosbags")
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.sources.ros1.live_source import Ros1LiveSource
    from console_tui.ui.app import ConsoleApp

    from support.feed import records
    from support.recordings import write_ros1_bag
    from support.ui import until

    bag = write_ros1_bag(tmp_path / "earlier.bag", records(300))
    ros1_nodes.rospy("rospy_node.py", "now", "--period", "0.1").expect("ready")
    queue = IntakeQueue()
    app = ConsoleApp(queue=queue, sources=[Ros1LiveSource(queue)], files=[str(bag)], utc=True)
    async with app.run_test(size=(140, 30)) as pilot:
        await until(pilot, lambda: len([r for r in app.main.store if r.node == "/now"]) >= 10, what="live rows")
        rows = list(app.main.store)
        sources = [r.source for r in rows]
        assert sources[:300] == ["earlier.bag"] * 300 and set(sources[300:]) == {ROSOUT_AGG}
        assert rows[0].topics == "/chatter"  # a ROS 1 bag's topics are kept too
        stamps = [r.stamp_ns for r in rows]
        assert stamps == sorted(stamps)


def test_the_launch_picks_ros1_when_a_master_answers(roscore, monkeypatch):
    import argparse

    from console_tui.control.ros1.logger_control import Ros1LoggerControl
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.run_app import _start_live
    from console_tui.sources.intake_process.parent import ProcessSource

    monkeypatch.setenv("ROS_VERSION", "2")  # a sourced ROS 2 says so; an answering master still wins
    args = argparse.Namespace(ros=None, demo=False, topic=None)
    sources: list = []
    cleanups: list = []
    control = _start_live(args, IntakeQueue(), sources, cleanups)
    try:
        assert [(type(s), s.kind) for s in sources] == [(ProcessSource, "ros1")]
        assert isinstance(control, Ros1LoggerControl)
    finally:
        for cleanup in cleanups:
            cleanup()
