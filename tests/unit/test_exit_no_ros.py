""" "ROS is not available" has one exit status across the app and its subcommands
(``EXIT_NO_ROS``, 2), each saying on stderr what is missing; no ROS is started."""

from __future__ import annotations

import socket
import sys

import pytest

from console_tui import cli
from console_tui.commands.arguments import EXIT_NO_ROS


@pytest.fixture
def no_rclpy(monkeypatch):
    """This Python without rclpy, and no ROS 1 in the environment."""
    monkeypatch.setitem(sys.modules, "rclpy", None)
    for name in ("ROS_MASTER_URI", "ROS_VERSION"):
        monkeypatch.delenv(name, raising=False)


@pytest.mark.parametrize(
    "argv",
    [
        ["--ros2"],  # the app, live
        ["tail", "--ros2"],
        ["watch", "--ros2"],
        ["loggers", "list", "--ros2", "--wait", "0"],
        ["loggers", "set", "/talker", "debug", "--ros2"],
        ["rosout"],
    ],
    ids=lambda argv: " ".join(argv[:2]),
)
def test_without_rclpy_every_command_exits_with_the_same_status(no_rclpy, capsys, argv):
    assert EXIT_NO_ROS == 2
    assert cli.main(argv) == EXIT_NO_ROS
    err = capsys.readouterr().err
    assert "ROS 2 (rclpy) is not available" in err and "Traceback" not in err


def test_no_ros1_master_is_the_same_status(monkeypatch, capsys):
    with socket.socket() as closed:  # a port nobody listens on
        closed.bind(("127.0.0.1", 0))
        port = closed.getsockname()[1]
    monkeypatch.setenv("ROS_MASTER_URI", f"http://127.0.0.1:{port}")
    monkeypatch.setenv("ROS_IP", "127.0.0.1")
    assert cli.main(["loggers", "list", "--ros1", "--wait", "0"]) == EXIT_NO_ROS
    assert "waiting for master at" in capsys.readouterr().err


def test_the_help_says_it(capsys):
    for argv in (["--help"], ["tail", "--help"], ["loggers", "--help"], ["rosout", "--help"]):
        with pytest.raises(SystemExit):
            cli.main(argv)
        out = capsys.readouterr().out
        assert f"{EXIT_NO_ROS}  bad command line" in out.replace("    ", "  ") and "not available" in out
