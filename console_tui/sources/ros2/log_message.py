"""A decoded ROS 2 log message (``rcl_interfaces/msg/Log``, from rclpy) as a record.

(ROS 1's ``rosgraph_msgs/Log`` is read by ``model.formats.ros1_log_msg`` straight from its bytes.)
"""

from __future__ import annotations

from typing import Any

from ...model.store.record import LogRecord


def log_to_record(message: Any, source: str) -> LogRecord:
    """Anything with the ROS 2 Log fields as a record."""
    stamp = message.stamp
    return LogRecord(
        stamp_ns=stamp.sec * 1_000_000_000 + stamp.nanosec,
        level=message.level,
        node=message.name,
        msg=message.msg,
        file=message.file,
        function=message.function,
        line=message.line,
        source=source,
    )
