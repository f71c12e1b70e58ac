"""What every text log format provides, and the loop that reads one into record batches."""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Iterable, Iterator
from typing import BinaryIO

from ..store.record import LogRecord
from .line_groups import TextLines
from .problems import Problems

DEFAULT_BATCH = 5_000


class TextFormat(ABC):
    """A text log format: how to recognise its first line and how to read its records."""

    #: Short name, as the command line and messages use it.
    name: str = ""
    #: What a user would call it.
    title: str = ""

    @abstractmethod
    def looks_like(self, first_line: str) -> bool:
        """Whether a file whose first recognisable line is this is in this format."""

    @abstractmethod
    def records(self, lines: TextLines, source: str, problems: Problems) -> Iterator[LogRecord]:
        """The records of a file, each with ``source``; bad parts go to ``problems``."""

    def for_file(self, name: str, mtime_ns: int = 0) -> TextFormat:
        """This format for reading one file (``name``: its file name, ``mtime_ns``: when it
        last changed); formats that take names or times from the file return a copy that
        knows them, the others themselves."""
        return self

    def notes(self) -> list[str]:
        """How this file was read, where a reader should know it (local times, times filled
        in): facts, not problems. Complete once the records have been read."""
        return []


class TextFormatWriter(ABC):
    """A format records can be saved in."""

    name: str = ""

    @abstractmethod
    def write(self, records: Iterable[LogRecord], stream: BinaryIO) -> Iterator[int]:
        """Write every record; yields the running count now and then (for progress and
        cancelling between yields)."""


def read_batches(
    stream: BinaryIO,
    text_format: TextFormat,
    source: str,
    problems: Problems,
    *,
    batch_size: int = DEFAULT_BATCH,
    lines: TextLines | None = None,
) -> Iterator[list[LogRecord]]:
    """Read a text log stream into batches of records (each at most ``batch_size``).

    Pass your own ``lines`` to watch ``lines.offset`` (bytes read) while this runs.
    A file that ends in the middle of a line is reported as probably truncated.
    """
    lines = lines if lines is not None else TextLines(stream, problems)
    batch: list[LogRecord] = []
    for record in text_format.records(lines, source, problems):
        batch.append(record)
        if len(batch) >= batch_size:
            yield batch
            batch = []
    if batch:
        yield batch
    if not lines.ended_with_newline:
        problems.add(
            "the file ends in the middle of a line: its last record may be cut off (truncated file?)",
            line=lines.lines_read,
        )
