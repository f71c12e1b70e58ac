"""Hostile ROS 1 masters and publishers (issue 33, items 1-3): real sockets on 127.0.0.1
answering malformed, dripping or huge. The live source stays up, says what is wrong, tries
again, keeps its memory bounded, and the good publisher's rows arrive."""

from __future__ import annotations

import subprocess
import sys

import pytest

from console_tui.control.ros1.logger_control import Ros1LoggerControl
from console_tui.ros.ros1.environment import Ros1Environment
from console_tui.ros.ros1.master import Ros1CallError, xmlrpc_call

from support.hostile_ros1 import (
    FakeMaster,
    FakePublisher,
    RunningSource,
    drip,
    huge_system_state,
    in_turn,
    reset_rss_peak,
    rss_peak_mb,
)
from support.ros1 import wait_for

GOOD_STATE = [[["/rosout", ["/good"]]], [], []]


@pytest.mark.parametrize(
    "answers",
    [
        {"getPid": in_turn("4242x", 4242)},
        {"getSystemState": in_turn("x", GOOD_STATE)},
        {"registerSubscriber": in_turn(5, None)},
    ],
    ids=["getPid", "getSystemState", "registerSubscriber"],
)
def test_one_malformed_master_answer_is_that_call_s_problem(answers):
    with FakePublisher() as good:
        answers = {k: (in_turn(v.values[0], [good.uri]) if v.values[-1] is None else v) for k, v in answers.items()}
        with FakeMaster([good.uri], **answers) as master, RunningSource(master) as running:
            wait_for(lambda: running.good_rows() >= 3, 30, "the good publisher's rows")
            assert running.source.status.running
            assert good.slave.calls["requestTopic"] >= 1


def test_a_master_always_malformed_is_said_and_asked_again():
    with FakeMaster([], getPid="4242x") as master, RunningSource(master) as running:
        wait_for(lambda: master.calls["getPid"] >= 3, 30, "getPid asked again")
        status = running.source.status
        assert status.running
        assert "getPid gave a malformed answer: 4242x" in status.problem and "trying again" in status.problem


def test_a_dripping_master_is_cut_off_at_the_call_s_deadline():
    with FakeMaster([], getPid=drip(4242, pause=0.2)) as master, RunningSource(master, call_timeout=0.5) as running:
        wait_for(lambda: "no answer within 0.5 s" in running.source.status.problem, 30, "the reason")
        assert running.source.status.running
        assert "waiting for master" in running.source.status.problem


def test_a_dripping_master_answer_is_refused_whole_by_xmlrpc_call():
    with (
        FakeMaster([], getPid=drip(4242, pause=0.1)) as master,
        pytest.raises(Ros1CallError, match=r"no answer within 0\.5 s"),
    ):
        xmlrpc_call(master.uri, "getPid", "/me", timeout=0.5)


def test_loggers_list_returns_against_a_dripping_master(tmp_path):
    with FakeMaster([], getSystemState=drip(GOOD_STATE, pause=0.2), getUri=drip("x", pause=0.2)) as master:
        env = {"ROS_MASTER_URI": master.uri, "ROS_IP": "127.0.0.1", "HOME": str(tmp_path), "PATH": "/usr/bin:/bin"}
        result = subprocess.run(
            [sys.executable, "-m", "console_tui", "loggers", "list", "--ros1", "--wait", "1"],
            capture_output=True,
            text=True,
            timeout=90,
            env=env,
        )
    assert "Traceback" not in result.stderr
    assert result.returncode != 0
    assert "no answer within" in result.stderr


def test_trickling_publishers_do_not_starve_a_good_one():
    tricklers = [
        FakePublisher(name=f"/slow{i}", request_topic=drip(["TCPROS", "127.0.0.1", 1], 0.2)) for i in range(20)
    ]
    try:
        with (
            FakePublisher() as good,
            FakeMaster([p.uri for p in tricklers]) as master,
            RunningSource(master, topic="/rosout") as running,
        ):
            wait_for(lambda: sum(p.slave.calls["requestTopic"] for p in tricklers) >= 16, 30, "the tricklers asked")
            master.publishers = [*master.publishers, good.uri]
            xmlrpc_call(running.source.slave_uri, "publisherUpdate", "/master", "/rosout", master.publishers)
            wait_for(lambda: running.good_rows() >= 3, 40, "the good publisher's rows")
            assert running.source.status.running
    finally:
        for publisher in tricklers:
            publisher.close()


def test_a_huge_system_state_is_refused_with_memory_bounded():
    with FakePublisher() as good, FakeMaster([good.uri], getSystemState=huge_system_state(600 << 20)) as master:
        reset_rss_peak()
        before = rss_peak_mb()
        with RunningSource(master, call_timeout=60) as running:
            wait_for(lambda: "MB refused" in running.source.status.problem, 120, "the refusal")
            wait_for(lambda: running.good_rows() >= 3, 30, "the good publisher's rows")
            assert running.source.status.running
        assert rss_peak_mb() - before < 250, f"peak RSS grew by {rss_peak_mb() - before:.0f} MB"


def test_the_logger_control_asks_the_master_only_while_watched():
    with FakeMaster(
        [], getSystemState=[[], [], [["/n/get_loggers", ["/n"]], ["/n/set_logger_level", ["/n"]]]]
    ) as master:
        control = Ros1LoggerControl(Ros1Environment(master.uri, "127.0.0.1", "127.0.0.1"), call_timeout=1.0)
        control.watch_graph(False)  # the UI's logger pane, closed
        control.start()
        try:
            wait_for(lambda: control.passes >= 30, 30, "the loggers thread turning")
            assert master.calls["getSystemState"] == 0
            control.watch_graph(True)  # the pane opened
            wait_for(lambda: [n.fqn for n in control.nodes] == ["/n"], 30, "the nodes")
        finally:
            control.close()


def test_a_large_answer_of_pythons_xmlrpc_server_as_rosmaster_is_read():
    """rosmaster is Python's XML-RPC server, which gzips large replies to a client that
    accepts it: the bounded call asks for them plain (the limit is of what is parsed)."""
    import threading
    from xmlrpc.server import SimpleXMLRPCServer

    server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False)
    server.register_function(lambda *_args: [1, "", [["/t", ["/n" * 1000]]] * 100], "getSystemState")
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        state = xmlrpc_call(f"http://127.0.0.1:{server.server_address[1]}/", "getSystemState", "/me")
        assert len(state) == 100
    finally:
        server.shutdown()
        server.server_close()
