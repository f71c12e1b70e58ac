"""What a launch prints on its terminal, read live as records (``console-tui run -- ...``).

Both launchers, line by line (``LaunchLines``), each line a record's start or a plain line of
a process, as ``mixed_output`` assembles them:

- ``ros2 launch`` (``launch``'s screen format, read by ``launch_log.parse_launch_line``):
  its own lines (``[INFO] [launch]: ...``, ``[ERROR] [talker-1]: process has died [pid 42,
  exit code 1, cmd '...'].``, an ERROR), and each line a process printed after its name
  (``[talker-1] [INFO] [<stamp>] [talker]: ...`` a record of that logger at its stamp;
  ``[talker-1] text`` a plain line of that process);
- ``roslaunch`` (``roslaunch/nodeprocess.py``, ``pmon.py``): ``process[talker-2]: started
  with pid [42]``, ``[talker-2] process has died [pid 42, exit code 1, cmd ...].`` (an ERROR,
  its ``log file: ...`` line with it), ``[talker-2] process has finished cleanly``,
  ``REQUIRED process [talker-2] has died!`` (an ERROR, with the lines of its frame), each a
  record of that process's node (``/talker``); a node's console line (``[ INFO]
  [<stamp>]: ...``, what a node with ``output="screen"`` prints, and every node's stderr)
  is a record of no known process (``UNATTRIBUTED``): roslaunch prints them unprefixed. So
  are its own other lines (the summary, ``ROS_MASTER_URI=...``) and what such nodes print.

A line ``Traceback (most recent call last):`` starts an ERROR record that its next lines
continue (the lines of a process continue its record before them). ``DeathAttribution``
gives a traceback of no known process to the process whose death roslaunch tells right
after it (a Python node's traceback, on its stderr, is its last words).

``live_records`` assembles lines as they come: a line without a time gets the time it
arrived, and a pause in the output (``None``) ends the record being built, so a traceback
is one record and a line printed a second later is not part of it. Blank lines are passed
over.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

from ..inert_text import strip_colour
from ..levels import Severity
from ..store.record import LogRecord
from .launch_log import parse_launch_line
from .mixed_output import FillCounts, Plain, Start, assemble, ros1_node_of_process
from .problems import Problems
from .ros1_console import Ros1ConsoleFormat

#: The node of a record no process is known for (a ``roslaunch`` line without a prefix);
#: named after the launch when it is shown.
UNATTRIBUTED = ""
TRACEBACK = "Traceback (most recent call last):"
#: Terminal controls launchers print that are no text: a window title (``ESC ] 2 ; ... BEL``).
_TERMINAL_CONTROL = re.compile(r"\x1b\][^\x07\x1b]*(?:\x07|\x1b\\)")
_STARTED = re.compile(r"process\[(?P<process>[^\]\s]+)\]: started with pid \[\d+\]\Z")
_ABOUT = re.compile(
    r"\[(?P<process>[^\]\s]+)\] (?P<what>process has died.*|process has finished cleanly.*|"
    r"escalating to SIG[A-Z]+|killing on exit)\Z",
    re.DOTALL,
)
_REQUIRED = re.compile(r"=*REQUIRED process \[(?P<process>[^\]\s]+)\] has died!")
_FRAME = re.compile(r"={20,}\Z")
_LOG_FILE = "log file: "
#: How long a traceback of no known process waits for a death to name its process.
DEATH_WAIT_NS = 2_000_000_000


def clean_line(text: str) -> str:
    """A terminal's line as text: without its carriage return, the terminal's echo of a
    Ctrl+C (``^C``), window titles and colour."""
    text = text.rstrip("\r").removeprefix("^C")
    if "\x1b" in text:
        text = strip_colour(_TERMINAL_CONTROL.sub("", text))
    return text


class LaunchLines:
    """Reads one launch's terminal lines (``parse``), remembering which process the lines
    after a death notice belong to."""

    def __init__(self) -> None:
        self._ros1, _ = Ros1ConsoleFormat().line_parser()
        #: The processes whose lines were seen (``talker-1``).
        self.processes: set[str] = set()
        #: The process whose death notice the next lines continue (``log file: ...``, a frame).
        self._dying = ""
        self._in_frame = False

    def parse(self, text: str) -> Start | Plain:
        item = self._parse(text)
        if item.owner:
            self.processes.add(item.owner)
        return item

    def _parse(self, text: str) -> Start | Plain:
        found = _STARTED.match(text)
        if found is not None:
            return self._process_line(found["process"], int(Severity.INFO), text)
        found = _ABOUT.match(text)
        if found is not None:
            what = found["what"]
            died = what.startswith("process has died")
            level = Severity.ERROR if died else Severity.WARN if what.startswith("escalating") else Severity.INFO
            self._dying = found["process"] if died else ""
            return self._process_line(found["process"], int(level), text)
        found = _REQUIRED.search(text)
        if found is not None:
            self._dying, self._in_frame = found["process"], True
            return self._process_line(found["process"], int(Severity.ERROR), text.lstrip("="))
        if self._dying and (text.startswith(_LOG_FILE) or self._in_frame):
            owner = self._dying
            if text.startswith(_LOG_FILE) and not self._in_frame:
                self._dying = ""
            if _FRAME.match(text):
                self._in_frame = False
                self._dying = ""
            return Plain(text, owner=owner)
        if text == "SUMMARY":  # roslaunch's summary: the lines after it, up to the next record, with it
            return Start(None, int(Severity.INFO), UNATTRIBUTED, text)
        ros1 = self._ros1(text)
        if isinstance(ros1, Start):
            return Start(ros1.stamp_ns, ros1.level, UNATTRIBUTED, ros1.text)
        item = parse_launch_line(text)
        if isinstance(item, Plain) and item.text.startswith(TRACEBACK):
            return Start(item.stamp_ns, int(Severity.ERROR), item.owner or UNATTRIBUTED, item.text, owner=item.owner)
        return item

    @staticmethod
    def _process_line(process: str, level: int, text: str) -> Start:
        return Start(None, level, ros1_node_of_process(process) or process, text, owner=process)


def live_records(
    lines: Iterable[str | None], clock: Callable[[], int], *, source: str, parser: LaunchLines | None = None
) -> Iterator[LogRecord]:
    """Records of a launch's lines as they come (``None``: a pause, the record being built is
    done); what gives no time takes ``clock()`` (nanoseconds) when it is read. A record's
    source is the process whose output it is (``talker-1``), else ``source``."""
    parse = (parser or LaunchLines()).parse

    def stamped(text: str) -> Start | Plain:
        item = parse(text)
        if item.stamp_ns is None:
            item.stamp_ns = clock()
        return item

    numbered = ((number, line) for number, line in enumerate(lines, 1) if line is None or line.strip())
    counts, problems = FillCounts(), Problems(source)
    yield from assemble(
        numbered,
        stamped,
        source=source,
        plain_node=UNATTRIBUTED,
        file_time_ns=0,
        counts=counts,
        problems=problems,
        owner_sources=True,
    )


@dataclass
class _Waiting:
    record: LogRecord
    since_ns: int


class DeathAttribution:
    """Holds a traceback of no known process until a death names its process (or
    ``DEATH_WAIT_NS`` passes); every other record passes at once (``take``, ``due``)."""

    def __init__(self, wait_ns: int = DEATH_WAIT_NS) -> None:
        self.wait_ns = wait_ns
        self._waiting: list[_Waiting] = []

    def take(self, record: LogRecord, now_ns: int) -> list[LogRecord]:
        """``record`` and whatever it lets go, in order."""
        if record.node == UNATTRIBUTED and record.msg.startswith(TRACEBACK):
            self._waiting.append(_Waiting(record, now_ns))
            return []
        if not self._waiting or not (record.level >= Severity.ERROR and "process has died" in record.msg):
            return [record]
        for waiting in self._waiting:
            waiting.record.node = record.node
        out = [waiting.record for waiting in self._waiting]
        self._waiting.clear()
        return [*out, record]

    def due(self, now_ns: int) -> list[LogRecord]:
        """The tracebacks that waited long enough."""
        out = [w.record for w in self._waiting if now_ns - w.since_ns >= self.wait_ns]
        self._waiting = [w for w in self._waiting if now_ns - w.since_ns < self.wait_ns]
        return out
