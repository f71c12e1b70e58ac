"""One log message, as every source produces it and every view reads it."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(slots=True)
class LogRecord:
    """A log message: the fields of ``rcl_interfaces/msg/Log`` plus where it came from.

    ``stamp_ns`` is nanoseconds since the Unix epoch; ``level`` is on the ROS 2 scale
    (DEBUG 10 .. FATAL 50); ``node`` is the logger name (usually the node's).
    ``source`` names the stream or file the record was read from. ``topics`` (ROS 1 only)
    lists the topics the node publishes, joined by ``,``; ``""`` when there are none or
    the source has no such field. ``robot`` names the robot (the source of a fleet: a ROS 2
    domain or a ROS 1 master, ``--domain``/``--master``/``--fleet``) it came from; ``""`` when
    the console reads one source. ``seq`` is assigned by
    the store when the record is added, numbering records in arrival order; -1 before.
    """

    stamp_ns: int
    level: int
    node: str
    msg: str
    file: str = ""
    function: str = ""
    line: int = 0
    source: str = ""
    topics: str = ""
    seq: int = -1
    robot: str = ""

    @property
    def stamp_sec(self) -> int:
        return self.stamp_ns // 1_000_000_000

    @property
    def stamp_nanosec(self) -> int:
        return self.stamp_ns % 1_000_000_000

    @property
    def location(self) -> str:
        """``file:function:line``, as rqt_console shows it."""
        return f"{self.file}:{self.function}:{self.line}"
