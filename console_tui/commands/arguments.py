"""Command-line arguments that several ``console-tui`` commands share."""

from __future__ import annotations

import argparse

from ..sources.ros_version import ROS1, ROS2


def add_log_format_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--log-format",
        metavar="FMT",
        help=(
            "the RCUTILS_CONSOLE_OUTPUT_FORMAT that ROS 2 log files were written with, for example "
            "'[{severity}] [{time}] [{name}]: {message}' (the default, always recognised; "
            "$RCUTILS_CONSOLE_OUTPUT_FORMAT is tried too)"
        ),
    )


def add_last_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--last",
        "--latest",
        action="store_true",
        help=(
            "the newest run in the ROS log directory ($ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log): "
            "the folder 'latest' points to, every log in it merged"
        ),
    )


def positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1")
    return value


def add_ros_version_arguments(parser: argparse.ArgumentParser) -> None:
    """``--ros1`` / ``--ros2``; the choice lands in ``args.ros`` (None: decide from the environment)."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--ros1",
        dest="ros",
        action="store_const",
        const=ROS1,
        help="ROS 1: talk to the master at ROS_MASTER_URI (default: ROS 1 when ROS_VERSION=1 or a master answers there, else ROS 2)",
    )
    group.add_argument("--ros2", dest="ros", action="store_const", const=ROS2, help="ROS 2, through rclpy")
