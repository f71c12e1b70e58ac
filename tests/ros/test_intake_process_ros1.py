"""The ROS 1 intake in its own process (what ``console-tui --ros1`` runs): records with every
field and the status come through the pipe; ``q`` ends the app and its intake process."""

from __future__ import annotations

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.intake_process.parent import ProcessSource
from console_tui.sources.live import open_live
from console_tui.sources.log_topics import ROSOUT_AGG

from support.quit import run_and_quit
from support.rosproc import pid_alive, wait_until

pytestmark = pytest.mark.ros1


def test_records_and_status_of_a_ros1_master_come_through_the_pipe(roscore, ros1_nodes):
    ros1_nodes.rospy("rospy_node.py", "piped_talker", "--period", "0.1", "--debug").expect("ready")
    queue = IntakeQueue()
    live = open_live(queue, ros=1)
    source = live.source
    assert isinstance(source, ProcessSource) and source.kind == "ros1"
    records: list = []

    def levels() -> set[int]:
        records.extend(queue.drain())
        return {r.level for r in records if r.node == "/piped_talker"}

    source.start()
    try:
        assert wait_until(lambda: levels() == {10, 20, 30, 40, 50}), source.status
        status = source.status
        assert (status.topic, status.publishers, status.problem, status.lost) == (ROSOUT_AGG, 1, "", 0)
        assert status.origin == f"ROS 1 {roscore.uri}" and status.running
        warn = next(r for r in records if r.node == "/piped_talker" and r.msg.startswith("warn "))
        assert (warn.file, warn.function, warn.source, warn.topics) == ("rospy_node.py", "main", ROSOUT_AGG, "/rosout")
        assert warn.line > 0 and warn.stamp_ns > 1_600_000_000 * 10**9
        # the frame loop in C decodes them (built beside the intake: a compiler is here)
        assert wait_until(lambda: source.status.path == "c+tcpros"), source.status
    finally:
        live.close()
    assert source.pid is not None and not pid_alive(source.pid)
    assert not source.status.running


def test_q_ends_console_tui_ros1_and_its_intake_process(roscore, ros1_env):
    intake, others, code = run_and_quit(ros1_env, "--ros1")
    assert code == 0
    assert not any(pid_alive(pid) for pid in intake | others), "a child of console-tui outlived it"
