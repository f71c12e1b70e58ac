"""What the formats of captured output and run logs share: lines that start records, lines
that do not, times that are missing, and names taken from a file's name.

These files mix log records with other text: a record's message continues on the lines
after it (a traceback, a printed environment), and programs print plain lines between
records. A format turns each line into a ``Start`` (a record begins here) or a ``Plain``
line; ``assemble`` makes records of them:

- a plain line continues the record before it when both are the same process's output
  (``owner``); otherwise (before any record, or another process's line) it becomes a
  record of its own, a *plain row*, at INFO, named after its process;
- a record without a time of its own (plain rows, launch lines printed without one) takes
  the time of the record before it; those before the first timed record take that
  record's time, and a file without any time the file's modification time.

Read live (``launch_output``), a line given as ``None`` says the output paused: the record
being built is done. Nothing is dropped: every line ends up in a record. Records are cut at
``MAX_RECORD_LINES`` lines or ``MAX_RECORD_CHARS`` characters; the lines after a cut
become plain rows.
"""

from __future__ import annotations

import re
import time
from abc import abstractmethod
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from functools import lru_cache

from ..inert_text import plural
from ..levels import Severity
from ..store.record import LogRecord
from . import line_groups
from .line_format import TextFormat
from .line_groups import TextLines
from .problems import Problems

#: Most records without a time held back waiting for the first time in a file; beyond
#: it they are given the file's modification time.
MAX_UNTIMED_AT_START = 10_000
_ROTATION = re.compile(r"\.\d+\Z")
_ROS1_PROCESS = re.compile(r"(?P<name>[A-Za-z_][A-Za-z0-9_]*(?:-[A-Za-z_][A-Za-z0-9_]*)*)-\d+\Z")
_INIT_NODE = re.compile(r"init_node, name\[(?P<name>[^\]\s]+)\]")
#: How a note about times without a zone begins (the detail view looks for it).
LOCAL_TIME_NOTE = "its times are local times without a zone"


@dataclass(slots=True)
class Start:
    """A line that starts a record; ``stamp_ns`` None when the line gives no time."""

    stamp_ns: int | None
    level: int
    node: str
    text: str
    owner: str = ""


@dataclass(slots=True)
class Plain:
    """A line that starts no record; ``owner`` is whose output it is (a process name);
    ``stamp_ns`` its time, when the line has one, should it become a row of its own."""

    text: str
    owner: str = ""
    stamp_ns: int | None = None


LineParser = Callable[[str], "Start | Plain"]


class MixedOutputFormat(TextFormat):
    """A format of output that mixes log records with other lines, read with ``assemble``.

    A format says how to read one line (``line_parser``) for the file it was made for
    (``for_file``: its name gives the process, its modification time the last resort for
    times); ``notes()`` says how times were filled in.
    """

    def __init__(self, file_name: str = "", mtime_ns: int = 0) -> None:
        self.file_name = file_name
        self.mtime_ns = mtime_ns
        self.counts = FillCounts()

    def for_file(self, name: str, mtime_ns: int = 0) -> MixedOutputFormat:
        return type(self)(name, mtime_ns)

    def notes(self) -> list[str]:
        return self.counts.notes()

    @abstractmethod
    def line_parser(self) -> tuple[LineParser, str]:
        """How to read this file's lines (called once per reading, so it may keep state), and
        the name of the file's plain rows when their lines name no process."""

    def records(self, lines: TextLines, source: str, problems: Problems) -> Iterator[LogRecord]:
        parse, plain_node = self.line_parser()
        yield from assemble(
            lines,
            parse,
            source=source,
            plain_node=plain_node,
            file_time_ns=self.mtime_ns,
            counts=self.counts,
            problems=problems,
        )


@dataclass
class FillCounts:
    """How the times of records were filled in while a file was read."""

    from_before: int = 0
    from_after: int = 0
    from_file: int = 0
    plain_rows: int = 0

    def notes(self) -> list[str]:
        notes = []
        if self.plain_rows:
            notes.append(f"{plural(self.plain_rows, 'plain line')} (no log record) became rows of their own, at INFO")
        if self.from_before:
            notes.append(
                f"{plural(self.from_before, 'record')} without a time of their own: the time of the record before"
            )
        if self.from_after:
            notes.append(f"{plural(self.from_after, 'record')} before the file's first time: that time")
        if self.from_file:
            notes.append(
                f"{plural(self.from_file, 'record')} with the file's modification time: the file gives no time"
            )
        return notes


@dataclass
class _Building:
    line: int
    stamp_ns: int | None
    level: int
    node: str
    owner: str
    lines: list[str] = field(default_factory=list)
    chars: int = 0
    is_record: bool = True


def assemble(
    lines: Iterable[tuple[int, str | None]],
    parse: LineParser,
    *,
    source: str,
    plain_node: str,
    file_time_ns: int,
    counts: FillCounts,
    problems: Problems,
    owner_sources: bool = False,
) -> Iterator[LogRecord]:
    """Records from numbered lines, as the module says. ``plain_node`` names the plain rows
    of a file whose lines name no process; ``file_time_ns`` is the last resort for times.
    ``owner_sources``: a record's source is the process whose output it is, where known."""
    waiting: list[_Building] = []  # records before the first time
    last_stamp: int | None = None
    current: _Building | None = None

    def finish(building: _Building) -> Iterator[LogRecord]:
        nonlocal last_stamp
        if building.stamp_ns is None:
            if last_stamp is None:
                waiting.append(building)
                if len(waiting) >= MAX_UNTIMED_AT_START:
                    yield from flush(file_time_ns, from_file=True)
                return
            building.stamp_ns = last_stamp
            counts.from_before += 1
        else:
            if waiting:
                yield from flush(building.stamp_ns, from_file=False)
            last_stamp = building.stamp_ns
        yield _record(building, building.owner or source if owner_sources else source)

    def flush(stamp_ns: int, *, from_file: bool) -> Iterator[LogRecord]:
        nonlocal last_stamp
        for building in waiting:
            building.stamp_ns = stamp_ns
            if from_file:
                counts.from_file += 1
            else:
                counts.from_after += 1
            yield _record(building, building.owner or source if owner_sources else source)
        waiting.clear()
        if from_file:
            last_stamp = stamp_ns

    for number, text in lines:
        if text is None:  # the output paused (read live): the record being built is done
            if current is not None:
                yield from finish(current)
                current = None
            continue
        item = parse(text)
        if isinstance(item, Start):
            if current is not None:
                yield from finish(current)
            current = _Building(number, item.stamp_ns, item.level, item.node, item.owner, [item.text], len(item.text))
            continue
        if (
            current is not None
            and current.is_record
            and current.owner == item.owner
            and len(current.lines) < line_groups.MAX_RECORD_LINES
            and current.chars + len(item.text) < line_groups.MAX_RECORD_CHARS
        ):
            current.lines.append(item.text)
            current.chars += len(item.text) + 1
            continue
        if current is not None:
            if current.is_record and current.owner == item.owner:
                problems.add(
                    f"record of more than {line_groups.MAX_RECORD_LINES:,} lines or "
                    f"{line_groups.MAX_RECORD_CHARS:,} characters: the lines after the cut are rows of their own",
                    line=current.line,
                )
            yield from finish(current)
        counts.plain_rows += 1
        node = item.owner or plain_node
        current = _Building(
            number, item.stamp_ns, int(Severity.INFO), node, item.owner, [item.text], len(item.text), False
        )
    if current is not None:
        yield from finish(current)
    if waiting:
        yield from flush(file_time_ns, from_file=True)


def _record(building: _Building, source: str) -> LogRecord:
    return LogRecord(
        stamp_ns=building.stamp_ns or 0,
        level=building.level,
        node=building.node,
        msg="\n".join(building.lines),
        source=source,
    )


def decimal_ns(text: str) -> int:
    """``1579418624.945503644`` (any number of decimals) as nanoseconds, exactly."""
    whole, _, fraction = text.partition(".")
    sign = -1 if whole.startswith("-") else 1
    return sign * (abs(int(whole)) * 1_000_000_000 + int((fraction + "000000000")[:9]))


def local_seconds(text: str) -> int:
    """``YYYY-MM-DD HH:MM:SS`` read as this computer's local time, to seconds since the epoch."""
    return _local_seconds(text, time.timezone, time.altzone)


@lru_cache(maxsize=4096)
def _local_seconds(text: str, _zone: int, _summer_zone: int) -> int:
    # the zone is part of the key: a changed TZ (time.tzset) must not reuse old answers
    return int(time.mktime(time.strptime(text, "%Y-%m-%d %H:%M:%S")))


def local_time_note() -> str:
    """What a reader says about a file whose times are local times without a zone."""
    zone, offset = time.strftime("%Z"), f"UTC{time.strftime('%z')}"
    shown = offset if zone in ("", "UTC", "GMT") else f"{zone}, {offset}"
    return f"{LOCAL_TIME_NOTE}: read as this computer's local time ({shown})"


def process_of_file(name: str) -> str:
    """The process a log file is named after: ``talker-2-stdout.log`` -> ``talker-2``,
    ``master.log.1`` -> ``master``; ``""`` for a name that says nothing."""
    stem = _ROTATION.sub("", name)
    for suffix in ("-stdout.log", "-stderr.log", ".log"):
        if stem.endswith(suffix):
            return stem[: -len(suffix)]
    return ""


def ros1_node_of_process(process: str) -> str:
    """The ROS 1 node a roslaunch process is: ``ns1-chat2-3`` -> ``/ns1/chat2``.

    roslaunch names a node's process ``<node name>-<counter>`` and its log files after it
    with ``/`` written ``-``; ROS 1 names hold no ``-``, so this is exact. ``""`` for a
    process not named that way.
    """
    match = _ROS1_PROCESS.match(process)
    if match is None:
        return ""
    return "/" + match["name"].replace("-", "/")


def rospy_node_name(message: str) -> str:
    """The node name in rospy's first log line (``init_node, name[/chat], pid[17136]``)."""
    match = _INIT_NODE.search(message)
    return match["name"] if match else ""
