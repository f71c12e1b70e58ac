"""The ROS 2 intake in its own process: what the in-process source gives, the same through
the pipe; and ``console-tui`` ends with ``q``, its intake process (and demo nodes) with it."""

from __future__ import annotations

import pytest
from conftest import next_domain_id
from test_ros2_live_source import serialized_log

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.sources.intake_process.parent import ProcessSource

from support.quit import run_and_quit
from support.rosproc import pid_alive, wait_until

pytestmark = pytest.mark.ros2


def collect(queue: IntakeQueue, enough, timeout: float = 20.0) -> list:
    records: list = []

    def done() -> bool:
        records.extend(queue.drain())
        return enough(records)

    wait_until(done, timeout)
    return records


def test_every_field_and_the_loss_counts_come_through_the_pipe(nodes):
    talker = nodes.start("talker.py", "--name", "piped_talker", "--namespace", "/ns", "--debug")
    logger = talker.expect("ready")["logger"]
    topic = "/piped_raw_log"
    queue = IntakeQueue()
    rosout = ProcessSource(queue, "ros2", topic="/rosout")
    raw = ProcessSource(IntakeQueue(), "ros2", topic=topic)
    rosout.start()
    raw.start()
    try:
        assert wait_until(lambda: rosout.status.publishers >= 1)
        talker.send({"cmd": "log_all", "tag": "piped"})
        logged = talker.expect("logged")["messages"]
        records = collect(queue, lambda got: sum(r.msg.startswith("piped ") for r in got) >= len(logged))
        mine = [r for r in records if r.msg.startswith("piped ")]
        assert [(r.level, r.msg, r.file, r.function, r.line) for r in mine] == [
            (m["level"], m["msg"], m["file"], m["function"], m["line"]) for m in logged
        ]
        assert {r.node for r in mine} == {logger} and {r.source for r in mine} == {"/rosout"}
        # The take loop in C is built beside the intake (the first run on a machine compiles it):
        # rclpy takes until it is ready, then the loop does.
        assert wait_until(lambda: rosout.status.path == "c+cdr"), rosout.status.path
        status = rosout.status
        assert (status.topic, status.running, status.lost) == ("/rosout", True, 0)

        publisher = nodes.start("raw_publisher.py", "--topic", topic)
        publisher.expect("ready")
        assert wait_until(lambda: raw.status.publishers >= 1)
        bad = ["00010000ffffffff", "0001000005000000060000001400000000ffffff"]
        publisher.send({"cmd": "publish", "hex": [*bad, serialized_log("after the bad ones")]})
        publisher.expect("published")
        after = collect(raw.queue, lambda got: any(r.msg == "after the bad ones" for r in got))
        assert [r.msg for r in after] == ["after the bad ones"]
        assert wait_until(lambda: raw.status.lost_undecodable == 2)
        assert raw.status.lost == 2 and "2 unreadable" in raw.status.loss_text()
    finally:
        rosout.stop()
        raw.stop()
    for source in (rosout, raw):
        assert source.pid is not None and not pid_alive(source.pid)


@pytest.mark.parametrize("args", [(), ("--demo",)], ids=["live", "demo"])
def test_q_ends_console_tui_and_its_intake_process(ros_env, args):
    if args:
        args = (*args, "--demo-domain", str(next_domain_id()))  # within the tests' domains
    intake, others, code = run_and_quit(ros_env, *args, others_expected=4 if args else 0)
    assert code == 0
    assert not any(pid_alive(pid) for pid in intake | others), "a child of console-tui outlived it"
    if args:
        assert len(others) == 4  # the demo nodes
