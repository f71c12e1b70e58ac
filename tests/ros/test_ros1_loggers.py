"""ROS 1 logger levels with real nodes: ``console-tui loggers list|get|set`` against roscore with
rospy and roscpp nodes, DEBUG rows appearing in the live stream, temporary levels, refusals."""

from __future__ import annotations

import time

import pytest
from test_cli_loggers import closed_pipe

from console_tui.commands.loggers import main as loggers_main
from console_tui.control.calls import SET
from console_tui.control.errors import LevelRefused

from support.ros1 import ROSCPP_LOGGER
from support.ros1_source import Collected

pytestmark = pytest.mark.ros1


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = loggers_main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def debug_rows(collected: Collected, node: str) -> list:
    return [r for r in collected.records if r.node == node and r.level == 10]


def test_list_get_and_set_debug_on_rospy_and_roscpp_nodes(roscore, ros1_nodes, roscpp_binary, capsys):
    ros1_nodes.rospy("rospy_node.py", "py", "--period", "0.1").expect("ready")
    ros1_nodes.roscpp("talk", "cpp", "100").expect("ready")
    with Collected() as got:
        got.wait_for("/py", "info ")
        got.wait_for("/cpp", "info ")
        status, out, err = run(capsys, "list", "--ros1")
        assert status == 0, err
        rows = [line.split("\t") for line in out.splitlines()]
        assert ["/cpp", "-", "logger-services"] in rows and ["/py", "-", "logger-services"] in rows
        assert not any(row[0].startswith("/console_tui_") for row in rows)  # our own node is left out
        assert not debug_rows(got, "/py") and not debug_rows(got, "/cpp"), "DEBUG is off by default"

        # rospy: its messages go through the logger 'rosout'
        status, out, err = run(capsys, "get", "py", "rosout")
        assert (status, out) == (0, "rosout\tINFO\tINFO\n"), err
        status, out, err = run(capsys, "set", "py", "rosout", "debug")
        assert (status, out) == (0, "rosout\tDEBUG\n"), err
        got.wait(lambda c: len(debug_rows(c, "/py")) >= 3, what="DEBUG rows from the rospy node")

        # roscpp: set by name, without get_loggers (which can crash roscpp on Debian 12)
        status, out, err = run(capsys, "set", "/cpp", ROSCPP_LOGGER, "DEBUG")
        assert (status, out) == (0, f"{ROSCPP_LOGGER}\tDEBUG\n"), err
        got.wait(lambda c: len(debug_rows(c, "/cpp")) >= 3, what="DEBUG rows from the roscpp node")

        # and off again
        assert run(capsys, "set", "py", "rosout", "info")[0] == 0
        assert run(capsys, "set", "cpp", ROSCPP_LOGGER, "info")[0] == 0
        time.sleep(0.5)
        count = len(got.records)
        got.wait(lambda c: len(c.records) > count + 20, what="more rows")
        later = got.records[count + 10 :]
        assert not any(r.level == 10 and r.node in ("/py", "/cpp") for r in later)


def test_get_lists_every_logger_of_a_rospy_node(roscore, ros1_nodes, capsys):
    ros1_nodes.rospy("rospy_node.py", "lister", "--period", "0").expect("ready")
    status, out, err = run(capsys, "get", "lister")
    assert status == 0, err
    names = [line.split("\t")[0] for line in out.splitlines()]
    assert "rosout" in names and "rospy" in names and names == sorted(names)
    status, out, _ = run(capsys, "get", "lister", "--json")
    assert '"name": "rosout"' in out


def test_set_node_level_sets_the_nodes_own_logger_as_on_ros2(roscore, ros1_nodes, roscpp_binary, capsys):
    """``loggers set NODE LEVEL`` (no logger) works on ROS 1 too: rospy nodes log through
    ``rosout``, roscpp nodes through ``ros.<package>`` under ``ros``; told without get_loggers.
    And ``ros2 log set``'s order, NODE LEVEL LOGGER."""
    ros1_nodes.rospy("rospy_node.py", "talker", "--period", "0.1").expect("ready")
    ros1_nodes.roscpp("talk", "cpp", "100").expect("ready")
    with Collected() as got:
        got.wait_for("/talker", "info ")
        got.wait_for("/cpp", "info ")
        assert run(capsys, "set", "/talker", "DEBUG")[:2] == (0, "rosout\tDEBUG\n")
        got.wait(lambda c: len(debug_rows(c, "/talker")) >= 3, what="DEBUG rows from the rospy node")
        assert run(capsys, "set", "/cpp", "DEBUG")[:2] == (0, "ros\tDEBUG\n")
        got.wait(lambda c: len(debug_rows(c, "/cpp")) >= 3, what="DEBUG rows from the roscpp node")
        assert run(capsys, "set", "cpp", "warn", ROSCPP_LOGGER)[:2] == (0, f"{ROSCPP_LOGGER}\tWARN\n")
        assert run(capsys, "set", "talker", "info", "rosout")[:2] == (0, "rosout\tINFO\n")
        # set --all: every node's own logger, rospy and roscpp alike (roscore's /rosout is roscpp)
        status, out, err = run(capsys, "set", "--all", "info")
        assert status == 0, err
        assert {"/talker\trosout\tINFO", "/cpp\tros\tINFO", "/rosout\tros\tINFO"} <= set(out.splitlines())
    assert run(capsys, "get", "talker", "rosout")[1] == "rosout\tINFO\tINFO\n"


def test_ros1_refusals_are_explicit(roscore, ros1_nodes, capsys):
    ros1_nodes.rospy("rospy_node.py", "strict", "--period", "0").expect("ready")
    status, _, err = run(capsys, "set", "strict", "unset")
    assert status == 2 and "cannot be unset" in err
    status, _, err = run(capsys, "set", "strict", "rosout", "unset")
    assert status == 2 and "cannot be unset" in err
    status, _, err = run(capsys, "get", "nobody", "--wait", "0.5")
    assert status == 3 and "no node 'nobody'" in err


def test_roscpp_answers_a_bad_level_with_ok_0_and_no_reason(roscore, ros1_nodes, roscpp_binary):
    from console_tui.control.ros1.logger_control import Ros1LoggerControl

    ros1_nodes.roscpp("talk", "cpp_bad", "200").expect("ready")
    control = Ros1LoggerControl()
    control.start()
    try:
        assert control.find_node("/cpp_bad", 5.0)
        future = control._submit("/cpp_bad", SET, [(ROSCPP_LOGGER, "LOUD")])
        with pytest.raises(LevelRefused) as refused:
            future.result(10)
        assert "no reason given: is 'LOUD' a level this node knows?" in str(refused.value)
        # a good level still works afterwards
        assert control.set_level("/cpp_bad", ROSCPP_LOGGER, 40).result(10) == {ROSCPP_LOGGER: 40}
    finally:
        control.close()


def test_temporary_debug_comes_back_by_itself(roscore, ros1_nodes, capsys):
    ros1_nodes.rospy("rospy_node.py", "brief", "--period", "0.1").expect("ready")
    with Collected() as got:
        got.wait_for("/brief", "info ")
        status, out, err = run(capsys, "set", "brief", "rosout", "debug", "--for", "1.5")
        assert status == 0, err
        assert out == "rosout\tDEBUG\nrosout\tINFO\n" and "then back to INFO" in err
        assert debug_rows(got, "/brief")
    assert run(capsys, "get", "brief", "rosout")[1] == "rosout\tINFO\tINFO\n"


def test_get_loggers_on_roscpp_as_debian_12_does_it(roscore, ros1_nodes, roscpp_binary, capsys):
    """rosconsole with log4cxx 1.x crashes roscpp nodes in get_loggers (ros/rosconsole#62): the
    reply is either the loggers or a failure that says so; setting by name still works on a
    node that survived, and a crashed one is reported as gone."""
    ros1_nodes.roscpp("talk", "fragile", "100").expect("ready")
    outcomes = []
    for _ in range(3):
        status, out, err = run(capsys, "get", "fragile")
        outcomes.append((status, out, err))
        if status != 0:
            break
    for status, out, err in outcomes:
        if status == 0:
            assert f"{ROSCPP_LOGGER}\t" in out or "ros\tINFO\tINFO" in out
        else:
            assert status == 4
            assert "dropped the get_loggers call" in err or "does not answer" in err, err
    status, out, err = run(capsys, "set", "fragile", ROSCPP_LOGGER, "warn")
    if outcomes[-1][0] == 0:
        assert status == 0, err
    else:
        assert status == 4 and "the node is gone" in err


def test_no_master_is_said_plainly(ros1_env, capsys):
    status, _, err = run(capsys, "list", "--ros1")
    assert status == 2 and "waiting for master at" in err and ros1_env["ROS_MASTER_URI"] in err


def test_a_closed_pipe_ends_list_and_get_quietly(roscore, ros1_nodes, ros1_env):
    ros1_nodes.rospy("rospy_node.py", "piped", "--period", "0.5").expect("ready")
    for args in (("list", "--ros1"), ("get", "piped", "--ros1", "--wait", "15")):
        result = closed_pipe(ros1_env, *args)
        assert result.returncode == 0, result.stderr
        assert "Traceback" not in result.stderr and "BrokenPipe" not in result.stderr
