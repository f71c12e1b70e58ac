"""ROS 1 console output, as roscpp and rospy print it and roslaunch saves it
(``<node>-<N>-stdout.log``) or a person captures it.

roscpp (rosconsole's default ``[${severity}] [${time}]: ${message}``, severity padded to 5)::

    [ INFO] [1579418624.945503644]: message
    [ WARN] [1579418624.945503644, 0.500000000]: message     (with simulated time: wall, sim)

rospy (the same format, times to the microsecond)::

    [INFO] [1624512197.562810]: message

The stamp is the wall-clock time (it orders a capture with every other log of the run);
simulated time, when a line carries it, is noted but not kept. The node is the process the
file is named after (``chat-2-stdout.log``: ``/chat``). Lines between records are the
output of the same program: they continue the record before them; lines before the first
record are rows of their own. Terminal colour codes are ignored.
"""

from __future__ import annotations

import re

from ..inert_text import plural, strip_colour
from ..levels import SEVERITY_WORDS
from .mixed_output import (
    LineParser,
    MixedOutputFormat,
    Plain,
    Start,
    decimal_ns,
    process_of_file,
    ros1_node_of_process,
)

_LEVELS = SEVERITY_WORDS
_LINE = re.compile(
    r"\[ ?(?P<level>DEBUG|INFO|WARN|ERROR|FATAL)\] \[(?P<wall>\d{1,20}\.\d{1,9})(?:, (?P<sim>-?\d{1,20}\.\d{1,9}))?\]: ?(?P<msg>.*)\Z",
    re.DOTALL,
)
#: Files of captured output, by name (rotated ones too): ``<process>-stdout.log``,
#: ``-stderr.log``, and a launched process's own ``<name>-<N>.log``. Read in this format
#: when no line of theirs says otherwise.
_CAPTURE_NAME = re.compile(r".+(?:-stdout|-stderr|-\d+)\.log(?:\.\d+)?\Z")


def is_capture_name(name: str) -> bool:
    """Whether a file is named as a process's captured output."""
    return _CAPTURE_NAME.match(name) is not None


class Ros1ConsoleFormat(MixedOutputFormat):
    name = "ros1-console"
    title = "ROS 1 console output"

    def __init__(self, file_name: str = "", mtime_ns: int = 0) -> None:
        super().__init__(file_name, mtime_ns)
        self.simulated = 0

    def looks_like(self, first_line: str) -> bool:
        return _LINE.match(strip_colour(first_line)) is not None

    def notes(self) -> list[str]:
        notes = self.counts.notes()
        if self.simulated:
            carry = "carries" if self.simulated == 1 else "carry"
            notes.insert(
                0, f"{plural(self.simulated, 'line')} {carry} simulated time too: the stamps are wall-clock times"
            )
        return notes

    def line_parser(self) -> tuple[LineParser, str]:
        process = process_of_file(self.file_name)
        node = ros1_node_of_process(process) or process
        match = _LINE.match

        def parse(text: str) -> Start | Plain:
            found = match(text) or ("\x1b" in text and match(strip_colour(text)))
            if not found:
                return Plain(text)
            if found["sim"] is not None:
                self.simulated += 1
            return Start(decimal_ns(found["wall"]), _LEVELS[found["level"]], node, found["msg"])

        return parse, node
