"""ROS 1 run logs in Python's logging layout: ``master.log``, ``roslaunch-<host>-<pid>.log``
and every rospy node's ``<node>-<N>.log`` (``~/.ros/log/<run_id>/``).

What rosgraph's ``python_logging.conf`` writes (format ``[%(name)s][%(levelname)s]
%(asctime)s: %(message)s``)::

    [rosmaster.main][INFO] 2021-06-24 05:23:17,010: initialization complete, waiting for shutdown

The logger, the level (DEBUG, INFO, WARNING, ERROR, CRITICAL), the local time to the
millisecond without a zone, the message. A message with newlines (a traceback, a printed
environment) continues on the lines after. rospy logs a node's own messages through the
logger ``rosout``: those records are named after the node instead (from the file's
``init_node, name[/chat]`` line, else from its roslaunch name ``chat-2.log``).
"""

from __future__ import annotations

import re

from ..levels import SEVERITY_WORDS
from .mixed_output import (
    LineParser,
    MixedOutputFormat,
    Plain,
    Start,
    local_seconds,
    local_time_note,
    process_of_file,
    ros1_node_of_process,
    rospy_node_name,
)

_LEVELS = SEVERITY_WORDS
_START = re.compile(
    r"\[(?P<logger>[^\]\n]*)\]\[(?P<level>DEBUG|INFO|WARNING|WARN|ERROR|CRITICAL|FATAL)\] "
    r"(?P<date>\d{4}-\d\d-\d\d \d\d:\d\d:\d\d),(?P<ms>\d{3}): ?(?P<msg>.*)\Z",
    re.DOTALL,
)
#: The logger rospy sends a node's own messages through.
ROSPY_USER_LOGGER = "rosout"


class PythonLogFormat(MixedOutputFormat):
    name = "rospy-log"
    title = "ROS 1 Python log"

    def looks_like(self, first_line: str) -> bool:
        return _START.match(first_line) is not None

    def notes(self) -> list[str]:
        return [local_time_note(), *self.counts.notes()]

    def line_parser(self) -> tuple[LineParser, str]:
        process = process_of_file(self.file_name)
        node = ros1_node_of_process(process)
        match = _START.match

        def parse(text: str) -> Start | Plain:
            nonlocal node
            found = match(text)
            if found is None:
                return Plain(text)
            logger, message = found["logger"], found["msg"]
            if logger == "rospy.client" and message.startswith("init_node"):
                node = rospy_node_name(message) or node
            try:
                stamp: int | None = local_seconds(found["date"]) * 1_000_000_000 + int(found["ms"]) * 1_000_000
            except (ValueError, OverflowError):  # no such date: the record takes the time before it
                stamp = None
            name = node if logger == ROSPY_USER_LOGGER and node else logger
            return Start(stamp, _LEVELS[found["level"]], name, message)

        return parse, node or process
