"""A systemd journal read to its end as a log file: a ``*.journal`` file, a journal directory
(as ``systemd-journal-remote`` writes a fleet's), or a ``journal:`` query for ``convert``.

``journalctl -o json`` reads it (``sources/journal/journalctl.py``: why, and how bounded);
entries become records as ``model/formats/journal_entry.py`` says, each named for its host
(``_HOSTNAME``) as its robot when the journal is not this machine's own.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path

from ...model.formats import FormatError
from ...model.formats.journal_entry import JournalEntries
from ...model.inert_text import plural
from ...model.store.record import LogRecord
from ..journal.journalctl import Journalctl, JournalQuery, JournalUnavailable, find_journalctl, local_journal_problem
from .log_file import Cancel, LogFile

BATCH_RECORDS = 5_000
KIND = "journal"


class JournalFile(LogFile):
    """A journal (``query``, never followed) read once; ``path`` and ``source`` name it."""

    kind = KIND
    unit = "entries"

    def __init__(self, path: Path, source: str, query: JournalQuery, *, template: str = "") -> None:
        super().__init__(path, source)
        self.query = query
        self.title = "systemd journal directory" if query.directory else "systemd journal"
        # A directory is a fleet's (systemd-journal-remote's): each record its host's robot.
        by_host = bool(query.directory)
        self.entries = JournalEntries(source=source, robot_from_host=by_host)
        if template:
            self.entries = JournalEntries(source=source, template=template, robot_from_host=by_host)

    @classmethod
    def of_path(cls, path: Path, source: str, *, template: str = "") -> JournalFile:
        """A journal file or directory; ``FormatError`` when journalctl is missing."""
        query = JournalQuery(directory=str(path)) if path.is_dir() else JournalQuery(files=(str(path),))
        try:
            find_journalctl()
        except JournalUnavailable as error:
            raise FormatError(f"{source}: a systemd journal, but {error}") from None
        return cls(path, source, query, template=template)

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        problem = local_journal_problem() if self.query.local else ""
        if problem:
            self.problems.add(problem)
            return
        try:
            journalctl = Journalctl(self.query)
        except JournalUnavailable as error:
            self.problems.add(str(error))
            return
        batch: list[LogRecord] = []
        try:
            for line in journalctl.lines():
                if line is None:
                    continue
                record = self.entries.line(line)
                if record is None:
                    continue
                batch.append(record)
                self.done += 1
                if len(batch) >= BATCH_RECORDS:
                    yield batch
                    batch = []
                    if cancel is not None and cancel.is_set():
                        return
            if batch:
                yield batch
        finally:
            journalctl.close()
        problem = journalctl.problem()
        if problem:
            self.problems.add(problem)
        unreadable = self.entries.unreadable + journalctl.too_long
        if unreadable:
            self.problems.add(f"{plural(unreadable, 'line')} of journalctl's output unreadable or too long")
        self.total = max(self.done, 1)

    def notes(self) -> list[str]:
        notes = []
        if self.entries.ros_records:
            notes.append(
                f"{plural(self.entries.ros_records, 'entry', 'entries')} read back as ROS 2 records (their console line)"
            )
        if self.entries.without_message:
            notes.append(f"{plural(self.entries.without_message, 'entry', 'entries')} without a message passed over")
        return notes

    def empty_reason(self) -> str:
        return "no journal entries in it" + (f" ({self.query.describe()})" if self.query.units else "")


def journal_file(query: JournalQuery, *, log_format: str = "") -> JournalFile:
    """A ``journal:`` query read to its end (``convert journal:nav.service``), named as it was written."""
    where = query.files[0] if query.files else query.directory
    name = "journal" + (":" + ",".join(query.units) if query.units else "") if not where else f"journal:{where}"
    return JournalFile(Path(where or "journal"), name, replace(query, follow=False), template=log_format)
