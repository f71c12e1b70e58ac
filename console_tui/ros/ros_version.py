"""Which ROS to talk to: ROS 1 or ROS 2, from the flags and the environment.

``--ros1`` / ``--ros2`` decide. Without them: ROS 1 when ``ROS_VERSION=1``, or when
``ROS_MASTER_URI`` is set and a master answers there; ROS 1 too when ``ROS_MASTER_URI`` is
set and this Python has no rclpy (a ROS 1 user is never sent to install rclpy: the console
waits for the master instead); else ROS 2.
"""

from __future__ import annotations

import importlib.util
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass

ROS1 = 1
ROS2 = 2


@dataclass(frozen=True)
class RosChoice:
    version: int
    #: Why, in a few words ("--ros1", "ROS_VERSION=1", "a master answers at URI", ...).
    reason: str
    #: ROS 2 chosen though ``ROS_MASTER_URI`` is set: that URI, where no master answered; else "".
    master_silent: str = ""


def rclpy_installed() -> bool:
    try:
        return importlib.util.find_spec("rclpy") is not None
    except (ImportError, ValueError):
        return False


def choose_ros(
    flag: int | None = None,
    environ: Mapping[str, str] | None = None,
    *,
    master_answers: Callable[[str], bool] | None = None,
    has_rclpy: Callable[[], bool] = rclpy_installed,
) -> RosChoice:
    """ROS 1 or ROS 2 for this run (``flag`` is 1 or 2 from ``--ros1``/``--ros2``, or None)."""
    if flag in (ROS1, ROS2):
        return RosChoice(flag, f"--ros{flag}")
    environ = os.environ if environ is None else environ
    if environ.get("ROS_VERSION", "").strip() == "1":
        return RosChoice(ROS1, "ROS_VERSION=1")
    master = environ.get("ROS_MASTER_URI", "").strip()
    if master:
        if master_answers is None:
            from .ros1.master import probe_master

            master_answers = probe_master
        if master_answers(master):
            return RosChoice(ROS1, f"a ROS 1 master answers at {master}")
        if not has_rclpy():
            return RosChoice(ROS1, f"ROS_MASTER_URI is set ({master}) and there is no rclpy")
    if master:
        return RosChoice(ROS2, "no ROS 1 master answers", master_silent=master)
    return RosChoice(ROS2, "ROS_MASTER_URI is not set")
