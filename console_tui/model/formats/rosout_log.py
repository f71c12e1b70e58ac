"""ROS 1 ``rosout.log``: the file the rosout node appends every ``/rosout`` message to.

What ``rosout.cpp`` (ros_comm ``tools/rosout``) writes per message::

    <sec>.<nsec 9 digits> <LEVEL> <name> [<file>:<line>(<function>)] [topics: <t1>, <t2>] <msg>

LEVEL is FATAL, ERROR, WARN, INFO or DEBUG (an unknown level as its number); the
``[topics: ...] `` part is left out when ``/rosout/omit_topics`` is set. Each file
starts with a blank line, another, and ``<time>  Node Startup``. A message with
newlines in it continues on the lines after.

Older rosout nodes (the log4cxx one of ROS Kinetic and before) wrote no name, and no
``]`` after the function::

    <sec>.<nsec> <LEVEL> [<file>:<line>(<function>) [topics: <t1>, <t2>] <msg>

Such records are read with an empty node name.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from ..levels import from_ros1
from ..record import LogRecord
from .problems import Problems, RecordError
from .text_format import TextFormat
from .textlines import LineKind, TextLines, group_lines, stray_text_problem

_LEVELS = {"DEBUG": 10, "INFO": 20, "WARN": 30, "ERROR": 40, "FATAL": 50}
_START = re.compile(r"\d+\.\d{9} (?:FATAL|ERROR|WARN|INFO|DEBUG|\d+) ")
_STARTUP = re.compile(r"\d+\.\d{9}  Node Startup\s*\Z")
_RECORD = re.compile(
    r"\A(?P<sec>\d+)\.(?P<nsec>\d{9}) (?P<level>FATAL|ERROR|WARN|INFO|DEBUG|\d+) (?P<name>[^ \n]*) "
    r"\[(?P<file>[^\n]*?):(?P<line>\d+)\((?P<function>[^\n]*?)\)\] "
    r"(?:\[topics: (?P<topics>[^\n]*?)\] )?(?P<msg>.*)\Z",
    re.DOTALL,
)
_OLD_RECORD = re.compile(
    r"\A(?P<sec>\d+)\.(?P<nsec>\d{9}) (?P<level>FATAL|ERROR|WARN|INFO|DEBUG|\d+) "
    r"\[(?P<file>[^\n]*?):(?P<line>\d+)\((?P<function>[^\n]*?)\) "
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
        for group in group_lines(lines, _classify, problems):
            if not group.is_record:
                stray_text_problem(group, problems, self.title)
                continue
            try:
                yield parse_rosout_record(group.text, source)
            except RecordError as error:
                problems.add(str(error), line=group.line)


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
    )
