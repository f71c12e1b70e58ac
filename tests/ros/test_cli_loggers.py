"""``console-tui loggers``: output and exit status, against real rclpy node processes."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from console_tui.commands.loggers import main
from console_tui.commands.loggers_arguments import EXIT_FAILED, EXIT_NOT_FOUND, EXIT_OK, EXIT_USAGE, parse_level

from support.rosproc import BusyProcesses


def run(capsys, *argv, runtime=None):
    status = main(list(argv), runtime)
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize(
    ("text", "level"), [("debug", 10), ("INFO", 20), ("Warning", 30), ("warn", 30), ("unset", 0), ("Inherited", 0)]
)
def test_level_names_any_case(text, level):
    assert parse_level(text) == level


@pytest.mark.parametrize(
    "argv",
    [["set", "/x", "loud"], ["set", "/x", "lg", "15"], ["set", "/x", "", "unset"], ["set", "/x", "a", "b", "info"]],
)
def test_bad_set_lines_exit_2_before_touching_ros(capsys, argv):
    status, out, err = run(capsys, *argv)
    assert status == EXIT_USAGE and out == ""
    assert err.startswith("console-tui loggers: ")


def test_unknown_level_names_the_accepted_ones(capsys):
    status, _out, err = run(capsys, "set", "/x", "loud")
    assert status == EXIT_USAGE
    assert "unknown level 'loud'" in err and "debug, info, warn, error, fatal" in err


@pytest.mark.parametrize(
    "argv",
    [["set", "--all", "/x", "debug"], ["set", "--all", "debug", "--for", "2"], ["set", "/x"]],
)
def test_bad_set_all_and_short_lines_exit_2(capsys, argv):
    status, out, err = run(capsys, *argv)
    assert status == EXIT_USAGE and out == "" and err.startswith("console-tui loggers: ")


def test_levels_lists_the_levels_without_ros(capsys):
    status, out, _ = run(capsys, "levels")
    assert status == EXIT_OK
    assert out.splitlines() == [
        "DEBUG\t10\t1",
        "INFO\t20\t2",
        "WARN\t30\t4",
        "ERROR\t40\t8",
        "FATAL\t50\t16",
        "UNSET\t0\t-",
    ]


@pytest.mark.ros2
def test_ros2_log_set_forms(nodes, ros_runtime, capsys):
    """``ros2 log set <node> <level> [<logger>]`` and ``set --all LEVEL`` with a real node."""
    nodes.start("talker.py", "--name", "talker").expect("ready")
    assert run(capsys, "set", "/talker", "DEBUG", "--wait", "15", runtime=ros_runtime)[:2] == (
        EXIT_OK,
        "talker\tDEBUG\n",
    )
    assert run(capsys, "set", "/talker", "error", "talker.sub", runtime=ros_runtime)[:2] == (
        EXIT_OK,
        "talker.sub\tERROR\n",
    )
    status, out, err = run(capsys, "get", "/talker", "talker", "talker.sub", runtime=ros_runtime)
    assert (status, out.splitlines()) == (EXIT_OK, ["talker\tDEBUG\tDEBUG", "talker.sub\tERROR\tERROR"]), err
    status, out, err = run(capsys, "set", "--all", "warn", runtime=ros_runtime)
    assert status == EXIT_OK, err
    assert "/talker\ttalker\tWARN" in out.splitlines()
    assert run(capsys, "get", "/talker", "talker", runtime=ros_runtime)[1] == "talker\tWARN\tWARN\n"


def test_usage_errors_exit_2(capsys):
    with pytest.raises(SystemExit) as exited:
        main(["frobnicate"])
    assert exited.value.code == EXIT_USAGE


@pytest.mark.ros2
def test_list_get_set_and_failures(nodes, ros_runtime, capsys):
    started = [
        nodes.start("talker.py", "--name", "alpha", "--namespace", "/ns"),
        nodes.start("talker.py", "--name", "beta", "--no-logger-service"),
    ]
    for process in started:
        process.expect("ready")

    # Waits for the node, then sets its own logger.
    assert run(capsys, "set", "alpha", "DEBUG", "--wait", "15", runtime=ros_runtime) == (
        EXIT_OK,
        "ns.alpha\tDEBUG\n",
        "",
    )
    status, out, err = run(capsys, "get", "/ns/alpha", "ns.alpha", "ns.alpha.sub", '""', runtime=ros_runtime)
    assert status == EXIT_OK, err
    assert out.splitlines() == ["ns.alpha\tDEBUG\tDEBUG", "ns.alpha.sub\tinherited\tDEBUG", '""\tINFO\tINFO']
    assert run(capsys, "set", "ns/alpha", "ns.alpha.sub", "error", runtime=ros_runtime)[:2] == (
        EXIT_OK,
        "ns.alpha.sub\tERROR\n",
    )
    status, out, _err = run(capsys, "get", "ns.alpha", "ns.alpha.sub", "--json", runtime=ros_runtime)
    assert json.loads(out) == {
        "node": "/ns/alpha",
        "loggers": [{"name": "ns.alpha.sub", "level": 40, "level_name": "ERROR", "effective": 40}],
    }

    status, out, err = run(capsys, "set", "beta", "debug", "--wait", "15", runtime=ros_runtime)
    assert status == EXIT_NOT_FOUND and out == ""
    assert "/beta has no logger services" in err and "enable_logger_service=True" in err

    status, out, _err = run(capsys, "list", "--json", "--wait", "0", runtime=ros_runtime)
    listed = {item["node"]: item["logger_services"] for item in json.loads(out)}
    assert status == EXIT_OK and listed == {"/ns/alpha": True, "/beta": False}
    status, out, _err = run(capsys, "list", "--wait", "0", runtime=ros_runtime)
    assert out.splitlines() == ["/beta\tbeta\tno-logger-services", "/ns/alpha\tns.alpha\tlogger-services"]

    status, out, err = run(capsys, "get", "gamma", "--wait", "0.5", runtime=ros_runtime)
    assert status == EXIT_NOT_FOUND and "no node 'gamma'" in err


@pytest.mark.ros2
def test_list_waits_for_every_node_under_load_and_says_how_long(nodes, ros_env):
    names = ["n1", "n2", "n3", "n4"]
    for process in [nodes.start("talker.py", "--name", name) for name in names]:
        process.expect("ready")
    with BusyProcesses(1):
        for _run in range(2):  # a fresh process each time: discovery from nothing
            result = subprocess.run(
                [sys.executable, "-m", "console_tui", "loggers", "list"],
                env=ros_env,
                capture_output=True,
                text=True,
                timeout=60,
            )
            assert result.returncode == EXIT_OK, result.stderr
            assert [line.split("\t")[0] for line in result.stdout.splitlines()] == [f"/{name}" for name in names]
            assert re.fullmatch(
                r"console-tui loggers: 4 nodes after \d+\.\d s, the graph unchanged for the last 2 s\n", result.stderr
            )


@pytest.mark.ros2
def test_list_finding_no_node_says_so_and_exits_3(ros_runtime, capsys):
    status, out, err = run(capsys, "list", "--wait", "1", runtime=ros_runtime)
    assert (status, out) == (EXIT_NOT_FOUND, "")
    assert err.startswith("console-tui loggers: no nodes found in 1.0 s (same ROS_DOMAIN_ID")


@pytest.mark.ros2
def test_set_for_puts_the_level_back(nodes, capsys):
    nodes.start("talker.py", "--name", "alpha").expect("ready")
    status, out, err = run(capsys, "set", "alpha", "warn", "--for", "0.5", "--wait", "15")
    assert status == EXIT_OK
    assert out.splitlines() == ["alpha\tWARN", "alpha\tinherited"]
    assert "then back to inherited" in err
    assert run(capsys, "get", "alpha")[1].splitlines()[0] == "alpha\tinherited\tINFO"


@pytest.mark.ros2
def test_a_busy_node_times_out_with_status_4(nodes, ros_env):
    alpha = nodes.start("talker.py", "--name", "alpha")
    alpha.expect("ready")
    alpha.send({"cmd": "block", "seconds": 30})
    alpha.expect("blocking")
    result = subprocess.run(
        [sys.executable, "-m", "console_tui", "loggers", "set", "/alpha", "debug", "--wait", "15", "--timeout", "0.5"],
        env=ros_env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == EXIT_FAILED, result.stderr
    assert result.stdout == ""
    assert "console-tui loggers: /alpha did not answer within 0.5 s" in result.stderr


def test_without_rclpy_exit_2_with_advice(capsys, monkeypatch):
    from console_tui.ros.ros2 import runtime
    from console_tui.ros.ros2.rclpy_loader import HOW_TO_GET_ROS2, RosUnavailable

    def unavailable():
        raise RosUnavailable(HOW_TO_GET_ROS2)

    monkeypatch.setattr(runtime, "load_rclpy", unavailable)
    status, out, err = run(capsys, "list")
    assert status == 2 and out == "" and "source /opt/ros" in err


def closed_pipe(env: dict, *args: str) -> subprocess.CompletedProcess:
    """``console-tui loggers ARGS | true``: the reader is gone before anything is printed."""
    command = f"set -o pipefail; {sys.executable} -m console_tui loggers {' '.join(args)} | true"
    return subprocess.run(["bash", "-c", command], env=env, capture_output=True, text=True, timeout=120)


@pytest.mark.ros2
def test_a_closed_pipe_ends_list_and_get_quietly(nodes, ros_env):
    nodes.start("talker.py", "--name", "piped").expect("ready")
    for args in (("list",), ("get", "piped", "--wait", "15")):
        result = closed_pipe(ros_env, *args)
        assert result.returncode == EXIT_OK, result.stderr
        assert "Traceback" not in result.stderr and "BrokenPipe" not in result.stderr
