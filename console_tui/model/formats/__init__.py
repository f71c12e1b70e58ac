"""Log files: reading and writing every text format console-tui knows (no ROS here).

- ``rqt_csv``: rqt_console's message files (ROS 2 and ROS 1 variants), read and written;
- ``jsonl``: JSON Lines, lossless, read and written;
- ``rcutils_log``: ROS 2 node log files (any ``RCUTILS_CONSOLE_OUTPUT_FORMAT``), read;
- ``rosout_log``: ROS 1 ``rosout.log``, read; the ``rosout.log`` of ``console-tui rosout``
  (ROS 2), read and written (``rotating_file`` rotates it);
- ``python_log``: ROS 1 run logs in Python's layout (``master.log``, ``roslaunch-*.log``,
  rospy nodes' ``<node>-N.log``), read;
- ``ros1_console``: roscpp and rospy console output (``<node>-N-stdout.log``, captures), read;
- ``launch_log``: ROS 2 ``launch.log`` and saved ``ros2 launch`` output, read.

``mixed_output`` is what the last three share (plain lines, missing times, names from
file names); ``detect`` picks a file's format from its first lines; ``save`` writes a file
atomically (``atomic``); ``print_format`` makes console lines for ``console-tui tail``.

Recordings (bags) are read by ``console_tui.sources.files``, which needs ROS libraries; the
``Log`` messages inside them and on the wire are decoded by ``ros2_log_msg`` (CDR) and
``ros1_log_msg``.
"""

from __future__ import annotations

from .detect import detect_text_format, recording_kind
from .jsonl import JsonLinesFormat
from .launch_log import LaunchLogFormat
from .line_format import TextFormat, read_batches
from .line_groups import TextLines
from .problems import FormatError, Problem, Problems, RecordError
from .python_log import PythonLogFormat
from .rcutils_log import DEFAULT_TEMPLATE, RcutilsLogFormat
from .ros1_console import Ros1ConsoleFormat
from .rosout_log import Ros2RosoutLogFormat, RosoutLogFormat
from .rqt_csv import RqtCsvFormat
from .save import SAVE_FORMATS, SaveCancelled, save_format_for, save_records


def text_formats(log_format: str | None = None, extra_templates: tuple[str, ...] = ()) -> list[TextFormat]:
    """The text formats to try on a file, in order.

    ``log_format`` (an ``RCUTILS_CONSOLE_OUTPUT_FORMAT`` template) is tried first when
    given; ``extra_templates`` (for example the environment's) after the default one.
    """
    formats: list[TextFormat] = []
    if log_format:
        formats.append(RcutilsLogFormat(log_format))
    formats += [RqtCsvFormat(), JsonLinesFormat(), RosoutLogFormat(), Ros2RosoutLogFormat()]
    if not log_format:
        formats.append(RcutilsLogFormat())
        formats += [RcutilsLogFormat(t) for t in extra_templates if t and t != DEFAULT_TEMPLATE]
    formats += [PythonLogFormat(), Ros1ConsoleFormat(), LaunchLogFormat()]
    return formats


__all__ = [
    "DEFAULT_TEMPLATE",
    "SAVE_FORMATS",
    "FormatError",
    "JsonLinesFormat",
    "LaunchLogFormat",
    "Problem",
    "Problems",
    "PythonLogFormat",
    "RcutilsLogFormat",
    "RecordError",
    "Ros1ConsoleFormat",
    "Ros2RosoutLogFormat",
    "RosoutLogFormat",
    "RqtCsvFormat",
    "SaveCancelled",
    "TextFormat",
    "TextLines",
    "detect_text_format",
    "read_batches",
    "recording_kind",
    "save_format_for",
    "save_records",
    "text_formats",
]
