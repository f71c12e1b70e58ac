"""The disk spool: batches waiting to be sent, in files that survive a crash and a reboot.

Each batch is one file, ``<number>-<records>.otlp.gz``: an OTLP ``ExportLogsServiceRequest``,
gzipped (as it is sent to a collector; the ClickHouse targets decode it). A batch is written to
a temporary name, flushed to the disk (``fsync``, then the directory's) and renamed: a file in
the spool is always whole. It is deleted only when the warehouse has taken it. The spool is
bounded (``max_bytes``): when a new batch would pass the bound, the oldest batches go (never
the one being sent), and their records are counted as lost. One process at a time uses a spool
(a lock on ``spool.lock``).
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import re
import threading
from dataclasses import dataclass
from pathlib import Path

_SEGMENT = re.compile(r"(\d{12})-(\d{1,9})\.otlp\.gz")
_TEMPORARY = ".tmp-"


class SpoolError(Exception):
    """The spool cannot be used (its directory, its lock); the text says why."""


@dataclass(frozen=True)
class Batch:
    """A batch in the spool: its number (in the order written), how many records, its size."""

    number: int
    records: int
    size: int

    @property
    def name(self) -> str:
        return f"{self.number:012d}-{self.records}.otlp.gz"


@dataclass(frozen=True)
class SpoolState:
    """How much waits in the spool, and what it dropped when full."""

    batches: int
    records: int
    size: int
    dropped_batches: int
    dropped_records: int


class Spool:
    """The batches of ``directory``, at most ``max_bytes`` of them."""

    def __init__(self, directory: str | os.PathLike[str], max_bytes: int, *, sync: bool = True) -> None:
        self.directory = Path(directory)
        self.max_bytes = max_bytes
        self._sync = sync
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
            self._lock_file = open(self.directory / "spool.lock", "a")
        except OSError as error:
            raise SpoolError(f"cannot use the spool {self.directory}: {error.strerror or error}") from None
        try:
            fcntl.flock(self._lock_file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self._lock_file.close()
            raise SpoolError(
                f"another console-tui ship uses the spool {self.directory} (give each its own --spool)"
            ) from None
        self._lock = threading.Lock()
        self._batches: dict[int, Batch] = {}
        #: The batch being sent: never dropped while it is.
        self.sending: int | None = None
        self.dropped_batches = 0
        self.dropped_records = 0
        for entry in os.scandir(self.directory):
            if entry.name.startswith(_TEMPORARY):  # a batch a crash left half written: never in the spool
                os.unlink(entry.path)
                continue
            found = _SEGMENT.fullmatch(entry.name)
            if found:
                batch = Batch(int(found.group(1)), int(found.group(2)), entry.stat().st_size)
                self._batches[batch.number] = batch
        self._next = max(self._batches, default=0) + 1

    def close(self) -> None:
        try:
            self._lock_file.close()  # the lock goes with it
        except OSError:
            pass

    def state(self) -> SpoolState:
        with self._lock:
            batches = list(self._batches.values())
            return SpoolState(
                len(batches),
                sum(b.records for b in batches),
                sum(b.size for b in batches),
                self.dropped_batches,
                self.dropped_records,
            )

    def write(self, data: bytes, records: int) -> Batch:
        """Keep a batch (whole on the disk before this returns); the oldest go if it would not fit."""
        with self._lock:
            number = self._next
            self._next += 1
        batch = Batch(number, records, len(data))
        temporary = self.directory / f"{_TEMPORARY}{batch.name}"
        with open(temporary, "wb") as file:
            file.write(data)
            if self._sync:
                file.flush()
                os.fsync(file.fileno())
        os.rename(temporary, self.directory / batch.name)
        if self._sync:
            self._sync_directory()
        with self._lock:
            self._batches[number] = batch
            self._keep_bound()
        return batch

    def _sync_directory(self) -> None:
        descriptor = os.open(self.directory, os.O_RDONLY)
        try:
            os.fsync(descriptor)
        finally:
            os.close(descriptor)

    def _keep_bound(self) -> None:
        """Drop the oldest batches (not the one being sent, not the newest) past ``max_bytes``."""
        total = sum(b.size for b in self._batches.values())
        for number in sorted(self._batches):
            if total <= self.max_bytes or len(self._batches) <= 1:
                break
            if number == self.sending:
                continue
            batch = self._batches.pop(number)
            total -= batch.size
            self.dropped_batches += 1
            self.dropped_records += batch.records
            self._unlink(batch)

    def _unlink(self, batch: Batch) -> None:
        try:
            os.unlink(self.directory / batch.name)
        except FileNotFoundError:
            pass

    def oldest(self) -> Batch | None:
        with self._lock:
            return self._batches[min(self._batches)] if self._batches else None

    def read(self, batch: Batch) -> bytes | None:
        """A batch's bytes; None when it is gone (dropped meanwhile)."""
        try:
            return (self.directory / batch.name).read_bytes()
        except FileNotFoundError:
            return None

    def delete(self, batch: Batch) -> None:
        """The warehouse took it (or it is unreadable): it goes."""
        with self._lock:
            self._batches.pop(batch.number, None)
            self._unlink(batch)
            if self._sync:
                self._sync_directory()


def batch_token(data: bytes) -> str:
    """What names a batch to a replicated table (``insert_deduplication_token``): made of its
    bytes, so the same every time it is sent, and never another batch's."""
    return "console-tui-" + hashlib.blake2b(data, digest_size=16).hexdigest()
