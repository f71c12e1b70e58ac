"""Severity levels: one table of their ROS 2 numbers, ROS 1 bits, names, letters and style
names; parsing."""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum


class Severity(IntEnum):
    """ROS 2 severities (``rcl_interfaces/msg/Log`` and ``LoggerLevel``)."""

    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


@dataclass(frozen=True)
class SeverityLevel:
    """One message severity, as every part of console-tui names and draws it."""

    #: The ROS 2 number (``rcl_interfaces/msg/Log``), the one console-tui keeps.
    severity: Severity
    #: The word shown and written: ``WARN``.
    name: str
    #: The ROS 1 level bit (``rosgraph_msgs/Log``).
    ros1: int
    #: The status line's letter.
    letter: str
    #: The style name: component classes end with it (``log-table--severity-warn``); the
    #: theme gives the colours (``ui/severity_styles.py``).
    style: str
    #: The colour ROS's own console prints it in (rcutils, rosconsole): an SGR escape, or "".
    ansi: str


#: The severities a message can have, lowest first: the one table of them.
SEVERITY_TABLE: tuple[SeverityLevel, ...] = (
    SeverityLevel(Severity.DEBUG, "DEBUG", 1, "D", "debug", "\x1b[32m"),
    SeverityLevel(Severity.INFO, "INFO", 2, "I", "info", ""),
    SeverityLevel(Severity.WARN, "WARN", 4, "W", "warn", "\x1b[33m"),
    SeverityLevel(Severity.ERROR, "ERROR", 8, "E", "error", "\x1b[31m"),
    SeverityLevel(Severity.FATAL, "FATAL", 16, "F", "fatal", "\x1b[31m"),
)

#: The severities a log message can have, lowest first.
MESSAGE_SEVERITIES: tuple[Severity, ...] = tuple(level.severity for level in SEVERITY_TABLE)

#: ROS 1 (``rosgraph_msgs/Log``) level bits to ROS 2 severities, and back.
ROS1_TO_ROS2: dict[int, int] = {level.ros1: int(level.severity) for level in SEVERITY_TABLE}
ROS2_TO_ROS1: dict[int, int] = {v: k for k, v in ROS1_TO_ROS2.items()}

#: The severity words of log lines (ROS consoles, Python logging) to ROS 2 numbers.
SEVERITY_WORDS: dict[str, int] = {level.name: int(level.severity) for level in SEVERITY_TABLE} | {
    "WARNING": int(Severity.WARN),
    "CRITICAL": int(Severity.FATAL),
}

_ALIASES: dict[str, Severity] = {level.name.lower(): level.severity for level in SEVERITY_TABLE} | {
    "unset": Severity.UNSET,
    "warning": Severity.WARN,
    "err": Severity.ERROR,
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


def severity_level(level: int) -> SeverityLevel:
    """The table's row for a message of ``level`` (levels between steps round down)."""
    return _BY_SEVERITY[severity_bucket(level)]


def severity_bucket(level: int) -> Severity:
    """The message severity a level counts under (levels between steps round down)."""
    for severity in reversed(MESSAGE_SEVERITIES):
        if level >= severity:
            return severity
    return Severity.DEBUG


_BY_SEVERITY: dict[Severity, SeverityLevel] = {level.severity: level for level in SEVERITY_TABLE}
