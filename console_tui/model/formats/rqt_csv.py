"""rqt_console's message files (its Save and Load buttons), ROS 2 and ROS 1 variants.

What rqt_console writes (``console_widget.py``, ``_handle_save_clicked``, the same code
on its ROS 2 branches and on melodic-devel):

- a header: the column names joined by ``;`` -- ``message;severity;node;stamp;location``
  (ROS 2) or ``message;severity;node;stamp;topics;location`` (ROS 1);
- one row per message: every field inside ``"``, fields joined by ``;``, a ``\\n`` after;
- the message with each ``"`` written as ``\\"`` and nothing else escaped (a newline in a
  message is written as it is, so a row can span lines); node and location unescaped;
- severity as the integer of its ROS version (ROS 2: 10..50; ROS 1: 1, 2, 4, 8, 16);
- stamp as ``sec.nsec`` with nsec zero-padded to 9 digits;
- topics (ROS 1) joined by ``,``; location as ``file:function:line``.

console-tui adds one column of its own, last, when the records came from a fleet (several
robots): ``robot``, the robot's name, escaped as a message is
(``message;severity;node;stamp;location;robot``). Files without robots are rqt_console's own.

Reading: a row starts at a line that begins with ``"`` but not with ``";"``. A
continuation line of a message begins with ``"`` only where the message ends with a
newline, and then with ``";"`` (the end of the message field); every other ``"`` in a
message is escaped. The fields are split at ``";"``, which an escaped message cannot
contain. (rqt_console's own loader drops the
newlines of multi-line messages; this reader keeps them.)
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from typing import BinaryIO

from ..levels import MESSAGE_SEVERITIES, ROS1_TO_ROS2, from_ros1, to_ros1
from ..store.record import LogRecord
from ..timefmt import stamp_text
from .line_format import TextFormat, TextFormatWriter
from .line_groups import LineGroup, LineKind, TextLines, group_lines, stray_text_problem
from .problems import Problems, RecordError

ROS2_COLUMNS = ("message", "severity", "node", "stamp", "location")
ROS1_COLUMNS = ("message", "severity", "node", "stamp", "topics", "location")
#: console-tui's own column, last, when records name their robot (a fleet's).
ROBOT_COLUMN = "robot"
_KNOWN_COLUMNS = frozenset((*ROS1_COLUMNS, ROBOT_COLUMN))
_ROS2_LEVELS = frozenset(int(s) for s in MESSAGE_SEVERITIES)
_STAMP = re.compile(r"(\d{1,20})\.(\d{1,18})\Z")
_LINE_NUMBER = re.compile(r"\d{1,12}\Z")
_WINDOWS_DRIVE = re.compile(r"[A-Za-z]:[\\/]")
_FLUSH_EVERY = 10_000
#: How many places a damaged row is tried to end at before it is given up.
_RECOVERY_ATTEMPTS = 1_000


def escape_message(text: str) -> str:
    """A message as rqt_console writes it: each ``"`` becomes ``\\"``."""
    return text.replace('"', '\\"')


def unescape_message(text: str) -> str:
    """The inverse of ``escape_message`` (rqt_console's loader does the same)."""
    return text.replace('\\"', '"')


def split_location(location: str) -> tuple[str, str, int]:
    """``file:function:line`` back into its parts.

    The line is after the last ``:``; the file ends at the first ``:`` (after a Windows
    drive letter), since C++ function names may hold ``::`` and Linux paths rarely hold
    ``:``. Text without a line number is kept whole as the file.
    """
    head, sep, line_text = location.rpartition(":")
    if not sep or not _LINE_NUMBER.match(line_text):
        return location, "", 0
    start = 2 if _WINDOWS_DRIVE.match(head) else 0
    cut = head.find(":", start)
    if cut < 0:
        return head, "", int(line_text)
    return head[:cut], head[cut + 1 :], int(line_text)


def _row(record: LogRecord, ros1: bool, robots: bool) -> str:
    severity = to_ros1(record.level) if ros1 else record.level
    fields = [escape_message(record.msg), str(severity), record.node, stamp_text(record.stamp_ns)]
    if ros1:
        fields.append(escape_message(record.topics))
    fields.append(record.location)
    if robots:
        fields.append(escape_message(record.robot))
    return ";".join(f'"{field}"' for field in fields) + "\n"


class RqtCsvWriter(TextFormatWriter):
    """Writes rqt_console's format byte for byte (UTF-8), ROS 2 or ROS 1 variant; with
    ``robots``, the ``robot`` column last."""

    def __init__(self, *, ros1: bool = False, robots: bool = False) -> None:
        self.ros1 = ros1
        self.robots = robots
        self.name = "rqt1" if ros1 else "rqt"

    def write(self, records: Iterable[LogRecord], stream: BinaryIO) -> Iterator[int]:
        columns = (*(ROS1_COLUMNS if self.ros1 else ROS2_COLUMNS), *((ROBOT_COLUMN,) if self.robots else ()))
        parts = [";".join(columns) + "\n"]
        count = 0
        for record in records:
            parts.append(_row(record, self.ros1, self.robots))
            count += 1
            if count % _FLUSH_EVERY == 0:
                stream.write("".join(parts).encode("utf-8", errors="replace"))
                parts.clear()
                yield count
        stream.write("".join(parts).encode("utf-8", errors="replace"))
        yield count


def parse_header(line: str) -> tuple[str, ...] | None:
    """The columns of an rqt_console header line, or None when it is not one."""
    columns = tuple(line.rstrip("\r").split(";"))
    if "message" not in columns or not set(columns) <= _KNOWN_COLUMNS or len(set(columns)) != len(columns):
        return None
    return columns


class RqtCsvFormat(TextFormat):
    """rqt_console message files; the header says which columns (and so which ROS)."""

    name = "rqt"
    title = "rqt_console CSV"

    def looks_like(self, first_line: str) -> bool:
        return parse_header(first_line) is not None

    def records(self, lines: TextLines, source: str, problems: Problems) -> Iterator[LogRecord]:
        numbered = iter(lines)
        columns: tuple[str, ...] | None = None
        for number, text in numbered:
            if not text.strip():
                continue
            columns = parse_header(text)
            if columns is None:
                problems.add(
                    f"no rqt_console header (expected {';'.join(ROS2_COLUMNS)!r}), found {text[:60]!r}",
                    line=number,
                )
                return
            break
        if columns is None:
            return
        ros1 = "topics" in columns
        for group in group_lines(numbered, _classify, problems):
            if not group.is_record:
                stray_text_problem(group, problems, self.title)
                continue
            try:
                yield _parse_row(group.text, columns, ros1, source)
            except RecordError as error:
                yield from self._row_then_stray_lines(group, columns, ros1, source, problems, error)

    def _row_then_stray_lines(
        self,
        group: LineGroup,
        columns: tuple[str, ...],
        ros1: bool,
        source: str,
        problems: Problems,
        error: RecordError,
    ) -> Iterator[LogRecord]:
        """A group that is no row may be a whole row followed by lines that belong to no
        row (a damaged file): read the row, and report those lines where they are."""
        lines = group.lines
        attempts = 0
        for end in range(len(lines) - 1):
            if not lines[end].rstrip("\r").endswith('"'):
                continue  # a row's last line ends with its closing quote
            attempts += 1
            if attempts > _RECOVERY_ATTEMPTS:
                break
            try:
                record = _parse_row("\n".join(lines[: end + 1]), columns, ros1, source)
            except RecordError:
                continue
            yield record
            stray_text_problem(LineGroup(group.line + end + 1, lines[end + 1 :], False), problems, self.title)
            return
        problems.add(str(error), line=group.line)


def _classify(line: str) -> LineKind:
    return LineKind.START if line.startswith('"') and not line.startswith('";"') else LineKind.MORE


def _parse_row(text: str, columns: tuple[str, ...], ros1: bool, source: str) -> LogRecord:
    # Blank lines after a row (CRLF ones too) belong to no message: a row ends with its closing quote.
    text = text.rstrip("\r\n")
    if len(text) < 2 or not text.endswith('"'):
        raise RecordError("row does not end with '\"' (truncated?)")
    values = text[1:-1].split('";"', len(columns) - 1)
    if len(values) != len(columns):
        raise RecordError(f"row has {len(values)} fields, the header {len(columns)}")
    fields = dict(zip(columns, values, strict=False))
    record = LogRecord(stamp_ns=0, level=20, node=fields.get("node", ""), msg="", source=source)
    record.msg = unescape_message(fields["message"])
    if "severity" in fields:
        record.level = _parse_severity(fields["severity"], ros1)
    if "stamp" in fields:
        match = _STAMP.match(fields["stamp"])
        if match is None:
            raise RecordError(f"stamp is not sec.nsec: {fields['stamp']!r}")
        record.stamp_ns = int(match.group(1)) * 1_000_000_000 + int(match.group(2))
    if "location" in fields:
        record.file, record.function, record.line = split_location(fields["location"])
    if fields.get("topics"):
        record.topics = unescape_message(fields["topics"])
    if fields.get(ROBOT_COLUMN):
        record.robot = unescape_message(fields[ROBOT_COLUMN])
    return record


def _parse_severity(text: str, ros1: bool) -> int:
    try:
        value = int(text)
    except ValueError:
        raise RecordError(f"severity is not a number: {text!r}") from None
    if ros1:
        if value not in ROS1_TO_ROS2:
            raise RecordError(f"unknown ROS 1 severity {value} (expected 1, 2, 4, 8 or 16)")
        return from_ros1(value)
    if value not in _ROS2_LEVELS:
        raise RecordError(f"unknown severity {value} (expected 10, 20, 30, 40 or 50)")
    return value
