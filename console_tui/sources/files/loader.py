"""Loading files in the background: merged batches into the UI's queue, with progress."""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ...model.formats import FormatError, Problem
from ...model.inert_text import plural
from ...model.store.intake_queue import IntakeQueue
from ...model.store.record import LogRecord
from ...model.store.record_batch import RecordColumns
from .folders import Expansion, LogPaths, expand_paths, source_names
from .log_file import LogFile, describe_error, reading_stopped
from .merge import merge_by_time
from .opener import open_log_paths
from .repeats import RepeatMerger

#: The loader waits while this many records wait in the queue (the UI is behind).
QUEUE_HIGH_WATER = 200_000
#: With more logs than this, each is opened only when the merge reaches its time.
MANY_FILES = 16


@dataclass(frozen=True)
class FileProgress:
    """One file of a load: its name, what it is, and how far reading it has got."""

    source: str
    title: str
    fraction: float
    problems: int
    failed: bool = False


@dataclass(frozen=True)
class LoadProgress:
    """A snapshot of a load, for a progress bar and a status line."""

    files: tuple[FileProgress, ...]
    records: int
    finished: bool
    cancelled: bool
    #: Still looking through the folders given for the logs in them (``files`` are the paths given).
    searching: bool = False
    #: Messages a rosout log and a node's own log file both held, made one record each.
    merged: int = 0

    @property
    def fraction(self) -> float:
        """0..1 over all files (each file counts the same)."""
        if self.finished:
            return 1.0
        if not self.files:
            return 0.0
        return sum(1.0 if f.failed else f.fraction for f in self.files) / len(self.files)


@dataclass
class OpenedLogs:
    """What opening paths gave: the logs opened, the problems of those that could not be,
    and the files of folders passed over (not logs by their names, or empty)."""

    files: list[LogFile] = field(default_factory=list)
    failures: list[Problem] = field(default_factory=list)
    skipped: list[Path] = field(default_factory=list)


def open_logs(paths: Sequence[str | os.PathLike[str]], *, log_format: str | None = None) -> OpenedLogs:
    """Open every path (a folder: every log in it); what cannot be read becomes a problem."""
    expansion = expand_paths(paths)
    opened = OpenedLogs(failures=folder_problems(expansion), skipped=expansion.skipped)
    many = len(expansion.logs) > MANY_FILES
    for log in expansion.logs:
        result = open_one(log, log_format, peek=many)
        if isinstance(result, Problem):
            opened.failures.append(result)
        else:
            opened.files.append(result)
    return opened


def open_files(
    paths: Sequence[str | os.PathLike[str]], *, log_format: str | None = None
) -> tuple[list[LogFile], list[Problem]]:
    """Open every path; the ones that cannot be read become problems, not exceptions."""
    opened = open_logs(paths, log_format=log_format)
    return opened.files, opened.failures


def folder_problems(expansion: Expansion) -> list[Problem]:
    """What went wrong with the folders opened: unreadable, or without a single log."""
    problems = [Problem(str(path), f"cannot list this folder: {reason}") for path, reason in expansion.unreadable]
    for folder in expansion.empty:
        inside = [p for p in expansion.skipped if folder in p.parents]
        what = f"no log files in this folder ({len(inside)} other files)" if inside else "no log files in this folder"
        problems.append(Problem(str(folder), what))
    return problems


def open_one(log: LogPaths, log_format: str | None, *, peek: bool = False) -> LogFile | Problem:
    """A log opened, or the problem that says why it cannot be (never an exception).
    ``peek``: also look at when its records begin (``LogFile.start_hint``)."""
    name = log.name
    try:
        opened = open_log_paths(log, log_format=log_format)
    except FormatError as error:
        return Problem(name, str(error).removeprefix(f"{name}: "))
    except Exception as error:  # a reading library's surprise on a damaged file
        return Problem(name, f"cannot read: {describe_error(error)}")
    if peek:
        opened.start_hint = opened.first_stamp()
    return opened


def robot_of(log: LogPaths, robots: Mapping[str, str]) -> str:
    """The robot named for ``log``'s path as given, or for the folder it was found in; or ""."""
    if not robots:
        return ""
    path = log.path.resolve()
    for given, robot in robots.items():
        place = Path(given).resolve()
        if place.name == "metadata.yaml":
            place = place.parent
        if path == place or place in path.parents:
            return robot
    return ""


def load_records(
    files: Sequence[LogFile],
    cancel: threading.Event | None = None,
    *,
    batch_size: int = 5_000,
    repeats: RepeatMerger | None = None,
) -> Iterator[list[LogRecord]]:
    """Every record of ``files`` merged by stamp, in batches (in the calling thread); a
    message both a rosout log and its node's own log file hold is one record (``repeats``,
    when given, counts them).

    A file that gives no record at all, and had no problem to explain it, gets one that
    says so (an empty result always comes with its reason). Files whose ``start_hint`` is
    known are opened only when the merge reaches that time, so a folder of thousands of
    logs holds only the files of one time open at once."""
    if not files:
        return iter(())
    hints = [file.start_hint for file in files]
    starts = hints if any(hint is not None for hint in hints) else None
    merged = merge_by_time([_counted(f, cancel) for f in files], batch_size=batch_size, starts=starts)
    return (repeats or RepeatMerger()).merge(merged, files)


def _counted(file: LogFile, cancel: threading.Event | None) -> Iterator[list[LogRecord]]:
    """A file's batches, counted; an error a reader did not expect ends that file only."""
    count = 0
    robot = file.robot
    try:
        for batch in file.batches(cancel):
            count += len(batch)
            if robot:
                for record in batch:
                    if not record.robot:
                        record.robot = robot
            yield batch
    except Exception as error:
        file.problems.add(reading_stopped(error))
    file.records = count
    if count == 0 and not len(file.problems) and not (cancel is not None and cancel.is_set()):
        file.problems.add(file.empty_reason())


class FileLoad:
    """Reads files in a background thread into ``sink`` (an ``IntakeQueue`` or a callable
    taking each batch, as ``RecordColumns``), merged by stamp, each record's ``source`` naming its file.

    From the UI thread: ``start()``, ``cancel()``, and read ``progress`` and
    ``problems()`` at any time. ``on_change`` (optional) is called from the loading
    thread after each batch and at the end, for example to post a Textual message.
    Files that cannot be opened are reported in ``problems()`` and the rest still load.
    """

    def __init__(
        self,
        paths: Sequence[str | os.PathLike[str]],
        sink: IntakeQueue | Callable[[RecordColumns], None],
        *,
        log_format: str | None = None,
        on_change: Callable[[], None] | None = None,
        robots: Mapping[str, str] | None = None,
    ) -> None:
        self.paths = list(paths)
        #: The robot of the files (and folders) given, by path as given (``--robot NAME``).
        self.robots = dict(robots or {})
        self.sink = sink
        self.log_format = log_format
        self.on_change = on_change
        self.cancel_event = threading.Event()
        self.files: list[LogFile] = []
        self.failures: list[Problem] = []
        self.error = ""
        self._names = source_names(self.paths)
        self._expanded = False
        #: Files of opened folders passed over (not logs by their names, or empty).
        self.skipped: list[Path] = []
        self._records = 0
        self._finished = False
        self._thread: threading.Thread | None = None
        self.repeats = RepeatMerger()

    def start(self) -> None:
        self._thread = threading.Thread(target=self._run, name="console-tui-file-load", daemon=True)
        self._thread.start()

    def cancel(self) -> None:
        """Stop reading soon; what was read stays. Safe from any thread."""
        self.cancel_event.set()

    def join(self, timeout: float | None = None) -> bool:
        """Wait for the thread; True once it has ended."""
        if self._thread is not None:
            self._thread.join(timeout)
            return not self._thread.is_alive()
        return True

    @property
    def finished(self) -> bool:
        return self._finished

    @property
    def progress(self) -> LoadProgress:
        opened = {f.source: f for f in self.files}
        failed = {p.source for p in self.failures}
        files = tuple(
            FileProgress(name, opened[name].title, opened[name].fraction, len(opened[name].problems))
            if name in opened
            else FileProgress(name, "", 0.0, 1 if name in failed else 0, failed=name in failed)
            for name in self._names
        )
        return LoadProgress(
            files, self._records, self._finished, self.cancel_event.is_set(), not self._expanded, self.repeats.merged
        )

    def problems(self) -> list[Problem]:
        """Everything that went wrong so far: files that could not be opened, then each
        file's problems (bad lines, truncation), in file order."""
        found = list(self.failures)
        for file in list(self.files):
            found.extend(file.problems)
            if file.problems.omitted:
                found.append(Problem(file.source, f"{plural(file.problems.omitted, 'more problem')} not listed"))
        if self.error:
            found.append(Problem("", self.error))
        return found

    def notes(self) -> dict[str, list[str]]:
        """How each file was read, where a person should know it (local times, times filled
        in), by source; complete once the load has finished."""
        return {file.source: notes for file in list(self.files) if (notes := file.notes())}

    def _run(self) -> None:
        try:
            expansion = expand_paths(self.paths)  # a large folder takes a while: here, not in the UI
            self.failures += folder_problems(expansion)
            self.skipped = expansion.skipped
            self._names = [log.name for log in expansion.logs]
            self._expanded = True
            many = len(expansion.logs) > MANY_FILES
            for log in expansion.logs:
                if self.cancel_event.is_set():
                    break
                result = open_one(log, self.log_format, peek=many)
                if isinstance(result, Problem):
                    self.failures.append(result)
                else:
                    result.robot = robot_of(log, self.robots)
                    self.files.append(result)
                self._changed()
            for batch in load_records(self.files, self.cancel_event, repeats=self.repeats):
                self._deliver(batch)
                if self.cancel_event.is_set():
                    break
        except Exception as error:  # the app must learn of it, never die of it
            self.error = f"loading stopped: {describe_error(error)}"
        finally:
            for file in self.files:
                file.close()
            self._finished = True
            self._changed()

    def _deliver(self, records: list[LogRecord]) -> None:
        batch = RecordColumns.from_records(records)
        sink = self.sink
        if isinstance(sink, IntakeQueue):
            while len(sink) > QUEUE_HIGH_WATER and not self.cancel_event.is_set():
                time.sleep(0.02)
            sink.put(batch)
        else:
            sink(batch)
        self._records += len(batch)
        self._changed()

    def _changed(self) -> None:
        if self.on_change is not None:
            try:
                self.on_change()
            except Exception:
                pass
