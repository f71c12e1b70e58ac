"""Importing rclpy, with a message that says how to get it when it is missing."""

from __future__ import annotations

import importlib

HOW_TO_GET_ROS2 = (
    "ROS 2 (rclpy) is not available in this Python.\n"
    "  - On a robot: source your ROS 2 install first, for example\n"
    "      source /opt/ros/$ROS_DISTRO/setup.bash\n"
    "    and run console-tui with the same Python (python3 -m console_tui).\n"
    "  - Anywhere else: install the optional extra with the rclpy wheels:\n"
    "      pip install 'console-tui[ros]'\n"
    "  - Or try it without ROS: console-tui --demo needs the same, or open a log file:\n"
    "      console-tui FILE"
)


class RosUnavailable(RuntimeError):
    """rclpy cannot be imported; the message says how to get it."""


def load_rclpy():
    """Import and return ``rclpy``, or raise ``RosUnavailable`` with set-up advice."""
    try:
        rclpy = importlib.import_module("rclpy")
        importlib.import_module("rcl_interfaces.msg")
    except Exception as error:  # ImportError, or a broken install raising anything
        raise RosUnavailable(f"{HOW_TO_GET_ROS2}\n(import failed: {error})") from None
    return rclpy
