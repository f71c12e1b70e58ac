"""The journal followed live: ``journalctl --follow -o json`` read by a thread, its entries
records in an ``IntakeQueue``, as the live ROS sources feed theirs.

The app and ``tail`` run it in the intake process (``intake_process.child``, kind
``journal``), where parsing JSON costs the app nothing; it has the sources' shape:
``start()``, ``stop()`` (journalctl killed) and ``status`` (a ``SourceStatus``: where it
reads, what it waits for, a problem: no journalctl, no journal, journalctl's complaint).
Lines that are no entry count as unreadable (``lost_undecodable``).
"""

from __future__ import annotations

import threading
from dataclasses import replace
from typing import Any

from ...model.formats.journal_entry import JournalEntries
from ...model.store.intake_queue import IntakeQueue
from ...model.store.record import LogRecord
from ...model.store.record_batch import RecordColumns
from ...system.thread_names import os_named
from ..status import SourceStatus
from .journalctl import Journalctl, JournalQuery, JournalUnavailable, local_journal_problem

#: Records handed on at most this many at once, and at least this often while they come.
BATCH_RECORDS = 2_000
PAUSE_S = 0.05
#: ``SourceStatus.path`` of a journal source.
PATH = "journalctl"


class JournalSource:
    """Follows ``query`` (made to follow) into ``queue``; ROS 2 lines read back with ``template``."""

    def __init__(self, queue: IntakeQueue, query: JournalQuery, *, template: str = "") -> None:
        self.queue = queue
        self.query = replace(query, follow=True)
        self.entries = JournalEntries(
            source="journal", template=template or JournalEntries.template, robot_from_host=bool(self.query.directory)
        )
        where = self.query.describe()
        self.status = SourceStatus(origin=where, path=PATH, hint=f"following {where}: no entries yet…")
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._journalctl: Journalctl | None = None

    def start(self) -> None:
        self._thread = threading.Thread(target=os_named(self._run), name="console-tui-journal", daemon=True)
        self._thread.start()

    def stop(self, timeout: float = 2.0) -> None:
        self._stop.set()
        journalctl = self._journalctl
        if journalctl is not None:
            journalctl.close()
        if self._thread is not None:
            self._thread.join(timeout)

    def _set(self, **changes: Any) -> None:
        self.status = replace(self.status, **changes)

    def _run(self) -> None:
        problem = local_journal_problem() if self.query.local else ""
        try:
            journalctl = self._journalctl = Journalctl(self.query)
        except JournalUnavailable as error:
            self._set(problem=str(error), running=False)
            return
        if self._stop.is_set():
            journalctl.close()
            return
        self._set(running=True, problem=problem)
        records: list[LogRecord] = []
        entries = self.entries
        try:
            for line in journalctl.lines(PAUSE_S):
                if self._stop.is_set():
                    break
                if line is not None:
                    record = entries.line(line)
                    if record is not None:
                        records.append(record)
                    if len(records) < BATCH_RECORDS:
                        continue
                self._hand_on(records, journalctl)
                records = []
            self._hand_on(records, journalctl)
        except (OSError, ValueError) as error:  # the pipe closed under us: stop() was called
            if not self._stop.is_set():
                self._set(problem=f"reading journalctl stopped: {error}")
        finally:
            journalctl.close()
        if not self._stop.is_set():
            ended = journalctl.problem() or "journalctl ended"
            self._set(problem=ended, running=False)
        else:
            self._set(running=False)

    def _hand_on(self, records: list[LogRecord], journalctl: Journalctl) -> None:
        if records:
            self.queue.put(RecordColumns.from_records(records))
        lost = self.entries.unreadable + journalctl.too_long + self.queue.dropped
        remark = journalctl.stderr[-1] if journalctl.stderr else ""
        if records and self.status.hint:
            self._set(hint="")
        if (lost, remark) != (self.status.lost, self.status.remark):
            undecodable = lost - self.queue.dropped
            self._set(lost=lost, lost_undecodable=undecodable, lost_queue=self.queue.dropped, remark=remark)
