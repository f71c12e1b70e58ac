"""``rosout.log``: the file a rosout node appends every ``/rosout`` message to.

**ROS 1** (read): what ``rosout.cpp`` (ros_comm ``tools/rosout``) writes per message::

    <sec>.<nsec 9 digits> <LEVEL> <name> [<file>:<line>(<function>)] [topics: <t1>, <t2>] <msg>

LEVEL is FATAL, ERROR, WARN, INFO or DEBUG (an unknown level as its number); the
``[topics: ...] `` part is left out when ``/rosout/omit_topics`` is set. Each file
starts with a blank line, another, and ``<time>  Node Startup``. A message with
newlines in it continues on the lines after.

Older rosout nodes (the log4cxx one of ROS Kinetic and before) wrote no name, and no
``]`` after the function::

    <sec>.<nsec> <LEVEL> [<file>:<line>(<function>) [topics: <t1>, <t2>] <msg>

Such records are read with an empty node name.

**ROS 2** (read and written): what ``console-tui rosout`` writes. The same layout
without topics, made exact so that every field reads back as it was sent::

    # console-tui rosout.log 1 (ROS 2): <sec>.<nsec> <LEVEL> <name> [<file>:<line>(<function>)] <msg>
    1763805921.123456789 INFO talker [/src/talker.py:42(tick)] Hello 1
    1763805921.223456789 ERROR nav.planner [planner.cpp:120(operator())] Planner failed:
    <tab>no path from (0, 0)
    <tab>to (5, 5)

- The first line of every file (rotated ones too) is the ``#`` header above.
- LEVEL is DEBUG, INFO, WARN, ERROR or FATAL for 10, 20, 30, 40, 50, any other level
  its ROS 2 number (``25``); the stamp is ``sec.nanosec``, nanosec 9 digits.
- A message with newlines in it continues on the lines after, each of them starting
  with one tab (taken off again when read), so no message line can pass for a record.
- In the name, ``%``, space and newline are written ``%25``, ``%20``, ``%0A``; in the
  file ``%``, ``(`` and newline; in the function ``%``, ``]`` and newline (as ``%XX``
  of their UTF-8 bytes). Names, files and functions rarely have any of them, so lines
  read as ROS 1's do. Everything else is written as it is, in UTF-8.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from urllib.parse import unquote

from ..levels import SEVERITY_TABLE, SEVERITY_WORDS, from_ros1
from ..store.record import LogRecord
from .line_format import TextFormat
from .line_groups import LineKind, TextLines, group_lines, group_records
from .problems import Problems, RecordError

_LEVELS = SEVERITY_WORDS
#: Message severities by name; any other level is written as its number.
_LEVEL_NAMES = {int(level.severity): level.name for level in SEVERITY_TABLE}
_START = re.compile(r"\d+\.\d{9} (?:FATAL|ERROR|WARN|INFO|DEBUG|\d{1,9}) ")
_STARTUP = re.compile(r"\d+\.\d{9}  Node Startup\s*\Z")
_RECORD = re.compile(
    r"\A(?P<sec>\d{1,20})\.(?P<nsec>\d{9}) (?P<level>FATAL|ERROR|WARN|INFO|DEBUG|\d{1,9}) (?P<name>[^ \n]*) "
    r"\[(?P<file>[^\n]*?):(?P<line>\d{1,12})\((?P<function>[^\n]*?)\)\] "
    r"(?:\[topics: (?P<topics>[^\n]*?)\] )?(?P<msg>.*)\Z",
    re.DOTALL,
)
_OLD_RECORD = re.compile(
    r"\A(?P<sec>\d{1,20})\.(?P<nsec>\d{9}) (?P<level>FATAL|ERROR|WARN|INFO|DEBUG|\d{1,9}) "
    r"\[(?P<file>[^\n]*?):(?P<line>\d{1,12})\((?P<function>[^\n]*?)\) "
    r"\[topics: (?P<topics>[^\n]*?)\] (?P<msg>.*)\Z",
    re.DOTALL,
)


def _classify(line: str) -> LineKind:
    if _START.match(line):
        return LineKind.START
    if _STARTUP.match(line):
        return LineKind.SKIP
    return LineKind.MORE


class RosoutLogFormat(TextFormat):
    name = "rosout"
    title = "ROS 1 rosout.log"

    def looks_like(self, first_line: str) -> bool:
        return _classify(first_line) is not LineKind.MORE

    def records(self, lines: TextLines, source: str, problems: Problems) -> Iterator[LogRecord]:
        groups = group_lines(lines, _classify, problems)
        return group_records(groups, lambda group: parse_rosout_record(group.text, source), problems, self.title)


def parse_rosout_record(text: str, source: str) -> LogRecord:
    match = _RECORD.match(text) or _OLD_RECORD.match(text)
    if match is None:
        raise RecordError(f"not a rosout.log record: {text[:60]!r}")
    level_text = match["level"]
    level = _LEVELS[level_text] if level_text in _LEVELS else from_ros1(int(level_text))
    return LogRecord(
        stamp_ns=int(match["sec"]) * 1_000_000_000 + int(match["nsec"]),
        level=level,
        node=match.groupdict().get("name") or "",
        msg=match["msg"],
        file=match["file"],
        function=match["function"],
        line=int(match["line"]),
        source=source,
        topics=",".join(filter(None, (topic.strip() for topic in (match["topics"] or "").split(",")))),
    )


# -- ROS 2: console-tui rosout's rosout.log ----------------------------------------------------

ROS2_HEADER = (
    "# console-tui rosout.log 1 (ROS 2): <sec>.<nsec> <LEVEL> <name> [<file>:<line>(<function>)] <msg>; "
    "lines after a record's first start with a tab; %XX escapes in name, file, function\n"
)
_ROS2_HEADER_START = "# console-tui rosout.log "
_ROS2_START = re.compile(r"-?\d+\.\d{9} (?:FATAL|ERROR|WARN|INFO|DEBUG|\d+) ")
_ROS2_RECORD = re.compile(
    r"\A(?P<sec>-?\d+)\.(?P<nsec>\d{9}) (?P<level>FATAL|ERROR|WARN|INFO|DEBUG|\d+) (?P<name>[^ \n]*) "
    r"\[(?P<file>[^(\n]*):(?P<line>\d+)\((?P<function>[^\]\n]*)\)\](?: (?P<msg>.*))?\Z",
    re.DOTALL,
)
_NAME_ESCAPES = str.maketrans({"%": "%25", " ": "%20", "\n": "%0A"})
_FILE_ESCAPES = str.maketrans({"%": "%25", "(": "%28", "\n": "%0A"})
_FUNCTION_ESCAPES = str.maketrans({"%": "%25", "]": "%5D", "\n": "%0A"})


def rosout_log_text(record: LogRecord) -> str:
    """One record as ``console-tui rosout`` writes it to rosout.log, newline included."""
    name, file, function, msg = record.node, record.file, record.function, record.msg
    # ``in`` tests: the aggregator's hot path, and these characters are rare.
    if "%" in name or " " in name or "\n" in name:
        name = name.translate(_NAME_ESCAPES)
    if "%" in file or "(" in file or "\n" in file:
        file = file.translate(_FILE_ESCAPES)
    if "%" in function or "]" in function or "\n" in function:
        function = function.translate(_FUNCTION_ESCAPES)
    if "\n" in msg:
        msg = msg.replace("\n", "\n\t")
    sec, nsec = divmod(record.stamp_ns, 1_000_000_000)
    level = _LEVEL_NAMES.get(record.level) or record.level
    return f"{sec}.{nsec:09d} {level} {name} [{file}:{record.line}({function})] {msg}\n"


def _classify_ros2(line: str) -> LineKind:
    if _ROS2_START.match(line):
        return LineKind.START
    if line.startswith(_ROS2_HEADER_START):
        return LineKind.SKIP
    return LineKind.MORE


class Ros2RosoutLogFormat(TextFormat):
    """The rosout.log ``console-tui rosout`` writes (see the module docstring)."""

    name = "rosout2"
    title = "console-tui rosout.log (ROS 2)"

    def looks_like(self, first_line: str) -> bool:
        return first_line.startswith(_ROS2_HEADER_START)

    def records(self, lines: TextLines, source: str, problems: Problems) -> Iterator[LogRecord]:
        groups = group_lines(lines, _classify_ros2, problems)
        return group_records(groups, lambda group: parse_ros2_rosout_record(group.lines, source), problems, self.title)


def parse_ros2_rosout_record(lines: list[str], source: str) -> LogRecord:
    """A record from its lines in a console-tui rosout.log (the first, then its continuations)."""
    match = _ROS2_RECORD.match(lines[0])
    if match is None:
        raise RecordError(f"not a rosout.log record: {lines[0][:60]!r}")
    msg = match["msg"] or ""
    if len(lines) > 1:
        rest = [line[1:] if line.startswith("\t") else line for line in lines[1:]]
        msg = "\n".join([msg, *rest])
    level_text = match["level"]
    name, file, function = match["name"], match["file"], match["function"]
    return LogRecord(
        stamp_ns=int(match["sec"]) * 1_000_000_000 + int(match["nsec"]),
        level=_LEVELS[level_text] if level_text in _LEVELS else int(level_text),
        node=unquote(name) if "%" in name else name,
        msg=msg,
        file=unquote(file) if "%" in file else file,
        function=unquote(function) if "%" in function else function,
        line=int(match["line"]),
        source=source,
    )
