"""Severity levels: ROS 2 numbers, ROS 1 numbers, names, and parsing."""

from __future__ import annotations

from enum import IntEnum


class Severity(IntEnum):
    """ROS 2 severities (``rcl_interfaces/msg/Log`` and ``LoggerLevel``)."""

    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


#: The severities a log message can have, lowest first.
MESSAGE_SEVERITIES: tuple[Severity, ...] = (
    Severity.DEBUG,
    Severity.INFO,
    Severity.WARN,
    Severity.ERROR,
    Severity.FATAL,
)

#: ROS 1 (``rosgraph_msgs/Log``) level bits to ROS 2 severities.
ROS1_TO_ROS2: dict[int, int] = {1: 10, 2: 20, 4: 30, 8: 40, 16: 50}
ROS2_TO_ROS1: dict[int, int] = {v: k for k, v in ROS1_TO_ROS2.items()}

_ALIASES: dict[str, Severity] = {
    "unset": Severity.UNSET,
    "debug": Severity.DEBUG,
    "info": Severity.INFO,
    "warn": Severity.WARN,
    "warning": Severity.WARN,
    "error": Severity.ERROR,
    "err": Severity.ERROR,
    "fatal": Severity.FATAL,
}


def severity_name(level: int) -> str:
    """Name of a ROS 2 level: ``WARN`` for 30; an unknown level reads as its number."""
    try:
        return Severity(level).name
    except ValueError:
        return str(level)


def parse_severity(text: str, *, allow_unset: bool = False) -> Severity:
    """Parse a severity name (any case, ``warning`` too) or its ROS 2 number.

    Raises ``ValueError`` with a message that lists the accepted names.
    """
    key = text.strip().lower()
    severity = _ALIASES.get(key)
    if severity is None and key.isdigit():
        try:
            severity = Severity(int(key))
        except ValueError:
            severity = None
    if severity is None or (severity is Severity.UNSET and not allow_unset):
        names = ", ".join(s.name.lower() for s in MESSAGE_SEVERITIES)
        if allow_unset:
            names += ", unset"
        raise ValueError(f"unknown level {text!r}: use one of {names}")
    return severity


def from_ros1(level: int) -> int:
    """ROS 1 level (1, 2, 4, 8, 16) to the ROS 2 level; unknown values map to the nearest."""
    if level in ROS1_TO_ROS2:
        return ROS1_TO_ROS2[level]
    if level <= 0:
        return int(Severity.DEBUG)
    # A combination of bits: take the highest one.
    highest = 1 << (level.bit_length() - 1)
    return ROS1_TO_ROS2.get(highest, int(Severity.FATAL))


def to_ros1(level: int) -> int:
    """ROS 2 level to the ROS 1 level bit; levels between steps round down."""
    for ros2 in sorted(ROS2_TO_ROS1, reverse=True):
        if level >= ros2:
            return ROS2_TO_ROS1[ros2]
    return ROS2_TO_ROS1[int(Severity.DEBUG)]


def severity_bucket(level: int) -> Severity:
    """The message severity a level counts under (levels between steps round down)."""
    for severity in reversed(MESSAGE_SEVERITIES):
        if level >= severity:
            return severity
    return Severity.DEBUG
