"""ROS 2 launch: ``launch.log`` (``~/.ros/log/<date>-<host>-<pid>/``) and the console output
people save from ``ros2 launch``.

What ``launch`` writes (``launch/logging``): its own loggers' lines, in the file with the
time (``{created:.7f} [{levelname}] [{name}]: {msg}``) and on the screen without it::

    1774882608.3200000 [INFO] [launch]: All log files can be found below /home/u/.ros/log/...
    [INFO] [launch]: Default logging verbosity is set to INFO
    [INFO] [talker-1]: process started with pid [4242]

and each line a process prints, after its name (``[{name}-{N}] {line}``; in the file with
the time before it when the process's output goes to the log)::

    [sllidar_node-2] [INFO] [1728089182.885399753] [sllidar_node]: SLLidar running ...
    [sllidar_node-2] a line the program printed

A process's line that is a ROS 2 log line (``[INFO] [<stamp>] [<logger>]: ...``) is a
record of that logger at its stamp; other lines of a process continue that process's record
before them, or are rows of their own named after the process. Lines that give no time take
the time of the line before. Levels: Python's (DEBUG, INFO, WARNING, ERROR, CRITICAL) and
rcutils' (DEBUG, INFO, WARN, ERROR, FATAL). Terminal colour codes are ignored.
"""

from __future__ import annotations

import re

from ..inert_text import strip_colour
from ..levels import SEVERITY_WORDS
from .mixed_output import LineParser, MixedOutputFormat, Plain, Start, decimal_ns, process_of_file

_LEVELS = SEVERITY_WORDS
_CREATED = r"(?:(?P<created>\d{1,20}\.\d{1,9}) )?"
_OWN = re.compile(
    _CREATED + r"\[(?P<level>DEBUG|INFO|WARNING|ERROR|CRITICAL)\] \[(?P<logger>[^\]\n]+)\]: ?(?P<msg>.*)\Z",
    re.DOTALL,
)
_PROCESS = re.compile(_CREATED + r"\[(?P<process>[^\]\s]+)\](?: (?P<rest>.*))?\Z", re.DOTALL)
_NODE_LINE = re.compile(
    r"\[(?P<level>DEBUG|INFO|WARN|ERROR|FATAL)\] \[(?P<stamp>-?\d{1,20}\.\d{1,9})\] "
    r"\[(?P<logger>[^\]\n]*)\]: ?(?P<msg>.*)\Z",
    re.DOTALL,
)
#: How launch names processes: the executable (or the name given) and a counter.
_PROCESS_NAME = re.compile(r"[^\]\s]+-\d+\Z")


class LaunchLogFormat(MixedOutputFormat):
    name = "launch"
    title = "ROS 2 launch log"

    def looks_like(self, first_line: str) -> bool:
        line = strip_colour(first_line)
        if _OWN.match(line):
            return True
        found = _PROCESS.match(line)
        return found is not None and _PROCESS_NAME.match(found["process"]) is not None

    def line_parser(self) -> tuple[LineParser, str]:
        return parse_launch_line, process_of_file(self.file_name)


def parse_launch_line(text: str) -> Start | Plain:
    """One line of launch output: a record's start, or a plain line (of a process)."""
    line = strip_colour(text) if "\x1b" in text else text
    found = _OWN.match(line)
    if found is not None:
        created = found["created"]
        stamp = decimal_ns(created) if created else None
        return Start(stamp, _LEVELS[found["level"]], found["logger"], found["msg"])
    found = _PROCESS.match(line)
    if found is None or found["process"] in _LEVELS:
        return Plain(text)
    process = found["process"]
    rest = found["rest"] or ""
    node_line = _NODE_LINE.match(rest)
    if node_line is not None:
        level = _LEVELS[node_line["level"]]
        return Start(decimal_ns(node_line["stamp"]), level, node_line["logger"], node_line["msg"], owner=process)
    created = found["created"]
    return Plain(rest, owner=process, stamp_ns=decimal_ns(created) if created else None)
