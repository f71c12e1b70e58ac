"""A decoded ROS log message (ROS 2 ``rcl_interfaces/msg/Log`` or ROS 1
``rosgraph_msgs/Log``, from any library) as a record."""

from __future__ import annotations

from typing import Any

from ..model.levels import from_ros1
from ..model.record import LogRecord


def log_to_record(message: Any, source: str, *, ros1: bool = False) -> LogRecord:
    """Anything with the Log fields as a record. ROS 1 messages keep their stamp in
    ``header`` and use levels 1..16, mapped to ROS 2's."""
    stamp = message.header.stamp if ros1 else message.stamp
    return LogRecord(
        stamp_ns=stamp.sec * 1_000_000_000 + stamp.nanosec,
        level=from_ros1(message.level) if ros1 else message.level,
        node=message.name,
        msg=message.msg,
        file=message.file,
        function=message.function,
        line=message.line,
        source=source,
    )
