"""One opened log file, whatever its format: record batches, progress, problems."""

from __future__ import annotations

import io
import os
import threading
from abc import ABC, abstractmethod
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import BinaryIO, cast

from ...model.formats import Problems, TextFormat, TextLines, read_batches
from ...model.store.record import LogRecord
from .rotated import PartsProblems, PartsStream

#: How much of a text log's start is read to learn when its records begin.
PEEK_BYTES = 64 * 1024

#: Anything with ``is_set()``: a ``threading.Event`` is what callers pass.
Cancel = threading.Event


def describe_error(error: BaseException) -> str:
    """An unexpected error of a reading library, for a user: its kind and its text, or
    what an error without text means (a library's internal check failed on bad data)."""
    text = str(error)
    if text:
        return f"{type(error).__name__}: {text}"
    return f"{type(error).__name__} (a check of the reading library failed on this data: the file is probably damaged)"


def reading_stopped(error: BaseException) -> str:
    """The problem of a file whose reading an unexpected error ended."""
    return f"reading stopped: {describe_error(error)}; what came before was read"


class LogFile(ABC):
    """An opened log file or recording, ready to be read once into record batches.

    ``source`` is what every record read from it carries in ``LogRecord.source``.
    ``done``/``total`` measure progress in ``unit`` (bytes for text files, messages or
    chunks for recordings); they may be read from any thread while ``batches`` runs.
    Problems found while reading (bad lines, truncation) go to ``problems``; reading
    goes on past them. Recordings also list the log ``topics`` they read.
    """

    kind: str = ""
    title: str = ""
    unit: str = "bytes"

    def __init__(self, path: Path, source: str) -> None:
        self.path = path
        self.source = source
        self.problems = Problems(source)
        self.total = 1
        self.done = 0
        #: Records read, once ``batches`` has run to its end (set by the loader).
        self.records = 0
        #: About when its records begin, when the loader looked (``first_stamp``).
        self.start_hint: int | None = None
        #: The robot its records came from (``--robot NAME`` before it), for those that name none.
        self.robot = ""

    @abstractmethod
    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        """The records, in batches, in the file's order; stops early once ``cancel`` is set."""

    def notes(self) -> list[str]:
        """How the file was read, where a person should know it (local times, times filled
        in): facts, not problems. Complete once ``batches`` has run."""
        return []

    def first_stamp(self) -> int | None:
        """About when its records begin (a look at its start, not a promise), or None when
        that is not cheap to know; lets a merge of many files open each file only when
        the merge reaches its time."""
        return None

    def empty_reason(self) -> str:
        """Why reading gave no record, when no problem says it already."""
        return "no log records in it"

    def close(self) -> None:  # noqa: B027 - most files hold nothing to release
        """Release what opening took (file handles); safe to call more than once."""

    @property
    def fraction(self) -> float:
        return min(1.0, self.done / self.total) if self.total > 0 else 1.0

    def __enter__(self) -> LogFile:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.source!r} {self.kind}>"


class TextLogFile(LogFile):
    """A text log file in one of ``console_tui.model.formats``' formats; with ``parts``, a
    log and its rotated files (oldest first, ``path`` the newest) read as one."""

    def __init__(self, path: Path, source: str, text_format: TextFormat, parts: Sequence[Path] = ()) -> None:
        super().__init__(path, source)
        self.parts = list(parts) or [path]
        infos = [os.stat(part) for part in self.parts]
        self._mtime_ns = max(info.st_mtime_ns for info in infos)
        self.format = text_format.for_file(path.name, self._mtime_ns)
        self.kind = text_format.name
        self.title = text_format.title if len(self.parts) == 1 else f"{text_format.title}, {len(self.parts)} files"
        self.total = max(1, sum(info.st_size for info in infos))
        if len(self.parts) > 1:
            self.problems = PartsProblems(source, self.parts)

    def notes(self) -> list[str]:
        return self.format.notes()

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        stream: BinaryIO | PartsStream
        if len(self.parts) == 1:
            stream = open(self.path, "rb")
        else:
            stream = PartsStream(self.parts)
            if isinstance(self.problems, PartsProblems):
                self.problems.stream = stream
        with stream:
            readable = cast(BinaryIO, stream)  # the parts read like one binary file
            lines = _ProgressLines(readable, self)
            for batch in read_batches(readable, self.format, self.source, self.problems, lines=lines):
                yield batch
                if cancel is not None and cancel.is_set():
                    return
        self.done = self.total

    def first_stamp(self) -> int | None:
        try:
            with open(self.parts[0], "rb") as stream:
                head = stream.read(PEEK_BYTES)
            text_format = self.format.for_file(self.path.name, self._mtime_ns)
            stamps: list[int] = []
            for batch in read_batches(io.BytesIO(head), text_format, self.source, Problems(self.source), batch_size=64):
                stamps += [record.stamp_ns for record in batch]
                if len(stamps) >= 64:
                    break
        except Exception:  # a look only: reading proper will say what is wrong
            return None
        return min(stamps) if stamps else None


class _ProgressLines(TextLines):
    """Lines that keep their file's ``done`` up to date."""

    def __init__(self, stream: BinaryIO, owner: LogFile) -> None:
        super().__init__(stream, owner.problems)
        self._owner = owner

    def __iter__(self) -> Iterator[tuple[int, str]]:
        owner = self._owner
        for item in super().__iter__():
            owner.done = self.offset
            yield item
