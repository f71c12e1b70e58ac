"""Entries of the systemd journal, as ``journalctl -o json`` prints them, read as log records.

One JSON object a line; every field a string, except binary ones (not UTF-8, or holding
control characters journald keeps as bytes): an array of byte values; a field over 4,096
bytes is ``null`` unless ``journalctl --all``. What an entry becomes:

- the level, from ``PRIORITY`` (syslog's 0-7, ``PRIORITY_LEVELS``): 0 emerg, 1 alert and
  2 crit are FATAL, 3 err ERROR, 4 warning WARN, 5 notice and 6 info INFO, 7 debug DEBUG;
  an entry without one INFO (journald's default for a stream);
- the node, from ``SYSLOG_IDENTIFIER`` (what ``journalctl`` shows before ``[pid]:``), else
  ``_COMM``, else the unit (``_SYSTEMD_UNIT``, ``_SYSTEMD_USER_UNIT``);
- the location, from ``CODE_FILE``, ``CODE_FUNC`` and ``CODE_LINE`` (``sd_journal_print``
  and python-systemd set them);
- the time, from ``_SOURCE_REALTIME_TIMESTAMP`` (when the process logged it), else
  ``__REALTIME_TIMESTAMP`` (when journald took it), microseconds since the epoch;
- the robot, with ``robot_from_host``, from ``_HOSTNAME`` (a fleet's journals, as
  ``systemd-journal-remote`` gathers them).

A message that is a ROS 2 console line is read back as the ROS record it was. That is what
``rcl_logging_syslog`` writes (checked against its source, ``src/rcl_logging_syslog.cpp``
at 0.1.1, and rcl's ``rcl/src/rcl/logging.c``): rcl formats every message with
``RCUTILS_CONSOLE_OUTPUT_FORMAT`` (by default ``[{severity}] [{time}] [{name}]: {message}``)
and hands the line to the logging backend, which calls ``syslog(priority, "%s", line)``
with ``openlog(<executable name>, LOG_PID, LOG_LOCAL1)`` and its priorities DEBUG 7,
INFO 6, WARN 4, ERROR 3, FATAL 1; journald stores the identifier as ``SYSLOG_IDENTIFIER``,
the facility as ``SYSLOG_FACILITY`` (17), the line as ``MESSAGE``. Such an entry's node is
the logger's name, its level and stamp the line's (the stamp the node put on its
``/rosout`` copy, to the nanosecond), its file, function and line those the format names.
So is the output of a ROS 2 launch run as a unit (``[talker-1] [INFO] [...] [talker]: ...``,
read as ``launch_log`` reads it). Other messages are kept as they are.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, field

from ..levels import Severity
from ..store.record import LogRecord
from .launch_log import parse_launch_line
from .mixed_output import Start
from .problems import RecordError
from .rcutils_log import DEFAULT_TEMPLATE, RcutilsLogFormat

#: syslog's priorities (``PRIORITY``) to ROS 2 severities.
PRIORITY_LEVELS: dict[int, int] = {
    0: int(Severity.FATAL),
    1: int(Severity.FATAL),
    2: int(Severity.FATAL),
    3: int(Severity.ERROR),
    4: int(Severity.WARN),
    5: int(Severity.INFO),
    6: int(Severity.INFO),
    7: int(Severity.DEBUG),
}
#: A journal line longer than this is not read (journalctl prints fields of at most 4,096
#: bytes unless ``--all``; a few dozen fields of that fit).
MAX_ENTRY_BYTES = 1 << 20
#: The longest message kept; the rest is cut, and the cut said.
MAX_MESSAGE_CHARS = 64 * 1024
#: The fields read: ``journalctl --output-fields`` (the cursor and timestamps always come).
FIELDS = (
    "MESSAGE",
    "PRIORITY",
    "SYSLOG_IDENTIFIER",
    "_COMM",
    "_SYSTEMD_UNIT",
    "_SYSTEMD_USER_UNIT",
    "CODE_FILE",
    "CODE_FUNC",
    "CODE_LINE",
    "_SOURCE_REALTIME_TIMESTAMP",
    "_HOSTNAME",
)
#: The node of an entry that names no process.
NO_NAME = "journal"


def field_text(value: object) -> str | None:
    """A field's value as text: a string as it is, bytes (an array of byte values) decoded
    as UTF-8 with stand-ins for what is not; ``None`` for a missing or withheld field."""
    if isinstance(value, str):
        return value
    if isinstance(value, list) and all(isinstance(byte, int) and 0 <= byte < 256 for byte in value):
        return bytes(value).decode("utf-8", "replace")
    if isinstance(value, list) and value:  # a field given twice in one entry: journalctl lists them
        return field_text(value[0])
    return None


@dataclass
class JournalEntries:
    """Reads journal entries into records (``record``), counting what it could not read.

    ``template`` is the ``RCUTILS_CONSOLE_OUTPUT_FORMAT`` ROS 2 lines are read back with;
    ``source`` what every record's source says; ``robot_from_host``: each record's robot is
    the entry's host.
    """

    source: str = "journal"
    template: str = DEFAULT_TEMPLATE
    robot_from_host: bool = False
    #: Lines that were no journal entry (not JSON, not an object, too long).
    unreadable: int = 0
    #: Entries without a message (or with one over 4,096 bytes that journalctl withheld).
    without_message: int = 0
    #: Entries read back as ROS 2 records.
    ros_records: int = 0
    _format: RcutilsLogFormat = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self._format = RcutilsLogFormat(self.template or DEFAULT_TEMPLATE)

    def line(self, data: bytes | str) -> LogRecord | None:
        """The record of one line of ``journalctl -o json`` (None: no record, counted)."""
        if len(data) > MAX_ENTRY_BYTES:
            self.unreadable += 1
            return None
        try:
            entry = json.loads(data)
        except ValueError:
            self.unreadable += 1
            return None
        if not isinstance(entry, dict):
            self.unreadable += 1
            return None
        return self.record(entry)

    def record(self, entry: Mapping[str, object]) -> LogRecord | None:
        """The record of one entry, or None when it has no message."""
        message = field_text(entry.get("MESSAGE"))
        if message is None:
            self.without_message += 1
            return None
        message = _bounded(message.rstrip("\n"))
        robot = (field_text(entry.get("_HOSTNAME")) or "") if self.robot_from_host else ""
        ros = self._ros_record(message)
        if ros is not None:
            self.ros_records += 1
            ros.robot = robot
            if not ros.file:  # the console line named no location: the entry's, if it has one
                ros.file = field_text(entry.get("CODE_FILE")) or ""
                ros.function = ros.function or field_text(entry.get("CODE_FUNC")) or ""
                ros.line = ros.line or _number(field_text(entry.get("CODE_LINE")))
            return ros
        return LogRecord(
            stamp_ns=_stamp_ns(entry),
            level=_level(entry),
            node=_node(entry),
            msg=message,
            file=field_text(entry.get("CODE_FILE")) or "",
            function=field_text(entry.get("CODE_FUNC")) or "",
            line=_number(field_text(entry.get("CODE_LINE"))),
            source=self.source,
            robot=robot,
        )

    def _ros_record(self, message: str) -> LogRecord | None:
        """A ROS 2 console line (``rcl_logging_syslog``'s, or a launch's) as its record."""
        try:
            return self._format.parse_record(message, self.source)
        except RecordError:
            pass
        if not message.startswith("["):
            return None
        item = parse_launch_line(message)
        if isinstance(item, Start) and item.owner and item.stamp_ns is not None:
            return LogRecord(item.stamp_ns, item.level, item.node, item.text, source=self.source)
        return None


def _bounded(message: str) -> str:
    if len(message) <= MAX_MESSAGE_CHARS:
        return message
    return message[:MAX_MESSAGE_CHARS] + f" … [cut: {len(message) - MAX_MESSAGE_CHARS:,} more characters]"


def _stamp_ns(entry: Mapping[str, object]) -> int:
    for name in ("_SOURCE_REALTIME_TIMESTAMP", "__REALTIME_TIMESTAMP"):
        micros = _number(field_text(entry.get(name)))
        if micros > 0:
            return micros * 1000
    return 0


def _level(entry: Mapping[str, object]) -> int:
    text = field_text(entry.get("PRIORITY"))
    if text is None or not text.strip().isdigit():
        return int(Severity.INFO)
    return PRIORITY_LEVELS.get(int(text), int(Severity.DEBUG))


def _node(entry: Mapping[str, object]) -> str:
    for name in ("SYSLOG_IDENTIFIER", "_COMM", "_SYSTEMD_UNIT", "_SYSTEMD_USER_UNIT"):
        text = field_text(entry.get(name))
        if text:
            return text[:256]
    return NO_NAME


def _number(text: str | None) -> int:
    """A decimal field's value (at most 20 digits), else 0."""
    if text is None:
        return 0
    text = text.strip()
    return int(text) if text.isdigit() and len(text) <= 20 else 0
