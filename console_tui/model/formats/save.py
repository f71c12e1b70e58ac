"""Saving records to a file: rqt_console's format or JSON Lines, always atomically."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Protocol

from ..atomic_file import atomic_output
from ..store.record import LogRecord
from .jsonl import JsonLinesWriter
from .line_format import TextFormatWriter
from .rqt_csv import RqtCsvWriter

#: Save formats by name: rqt_console ROS 2 (``rqt``), its ROS 1 variant, JSON Lines; each
#: made with ``robots``: whether the records name their robots (rqt_console's gets a column).
SAVE_FORMATS: dict[str, Callable[..., TextFormatWriter]] = {
    "rqt": lambda robots=False: RqtCsvWriter(robots=robots),
    "rqt1": lambda robots=False: RqtCsvWriter(ros1=True, robots=robots),
    "jsonl": lambda robots=False: JsonLinesWriter(),
}
_JSONL_SUFFIXES = (".jsonl", ".ndjson", ".json")


class Cancellable(Protocol):
    def is_set(self) -> bool: ...


class SaveCancelled(Exception):
    """The save was cancelled; the target file was left as it was."""


def save_format_for(path: str | os.PathLike[str]) -> str:
    """The save format a file name asks for: JSON Lines for ``.jsonl``/``.ndjson``/``.json``,
    rqt_console's format for anything else."""
    return "jsonl" if Path(path).suffix.lower() in _JSONL_SUFFIXES else "rqt"


def save_records(
    records: Iterable[LogRecord],
    path: str | os.PathLike[str],
    save_format: str | None = None,
    *,
    cancel: Cancellable | None = None,
    progress: Callable[[int], None] | None = None,
    robots: bool | None = None,
) -> int:
    """Write ``records`` to ``path`` in ``save_format`` (default: from the name); returns
    how many were written.

    The file is replaced atomically: if this raises (``OSError``, or ``SaveCancelled``
    when ``cancel`` is set), a file already at ``path`` is untouched. ``progress`` is
    called with the running count every few thousand records. Iterate over a snapshot
    (or from the thread that owns the store), not over a store another thread changes.
    ``robots`` says whether records name their robot (None: looked for in a sequence of
    records; records from an iterator are taken to name none).
    """
    name = save_format or save_format_for(path)
    if name not in SAVE_FORMATS:
        raise ValueError(f"unknown save format {name!r}: use one of {', '.join(SAVE_FORMATS)}")
    if robots is None:
        robots = isinstance(records, Sequence) and any(record.robot for record in records)
    writer = SAVE_FORMATS[name](robots=robots)
    count = 0
    with atomic_output(path) as stream:
        for count in writer.write(records, stream):
            if cancel is not None and cancel.is_set():
                raise SaveCancelled(f"save to {os.fspath(path)} cancelled")
            if progress is not None:
                progress(count)
    return count
