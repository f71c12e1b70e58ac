"""Where the store's spilled chunks live: segment files in a private directory.

Blobs are appended to the newest segment (``append``) and read back from anywhere with
``os.pread`` (``read``: from any thread). A segment is a run of records, each a kind and a
length, then the blob (``CHUNK``: a chunk, ``chunk_blob.py``; ``TABLES``: strings the chunks
after it name; ``KEPT``: the chunks a kept session held at its end), so a kept history can be
read again from its files alone. When the store
drops its last chunk in a segment (``release``), the file goes. Every write goes whole or
not at all: a failed one (a full disk, a file size limit) is cut off again and raised, so
that the store can keep that chunk in memory instead and say why. A new segment is begun
only with ``MIN_FREE_BYTES`` free on the disk, so the history never fills it to the last
byte. ``write`` is how bytes reach a file (``os.write``; tests give one that fails).
"""

from __future__ import annotations

import errno
import os
import struct
import threading
from collections import Counter
from collections.abc import Callable, Iterator
from pathlib import Path

SEGMENT_BYTES = 64 << 20
#: A new segment needs this much free on the disk (else writing stops: "the disk is full").
MIN_FREE_BYTES = 256 << 20
_RECORD = struct.Struct("<4sI")
CHUNK = b"CTC1"
TABLES = b"CTT1"
#: The chunks a kept session's store held at its end (``pack_kept``): written last, when it ends.
KEPT = b"CTK1"
_KEPT_HEAD = struct.Struct("<I")
_KEPT_CHUNK = struct.Struct("<IQ")
_NAME = "segment-{:06d}.ctc"


class SpillFiles:
    """Segment files in ``directory`` (which must exist and be private: ``history_dir.py``)."""

    def __init__(
        self,
        directory: Path,
        *,
        segment_bytes: int = SEGMENT_BYTES,
        min_free_bytes: int = MIN_FREE_BYTES,
        write: Callable[[int, bytes], int] = os.write,
    ) -> None:
        self.directory = directory
        self.segment_bytes = segment_bytes
        self.min_free_bytes = min_free_bytes
        self._write = write
        self._lock = threading.Lock()
        self._fds: dict[int, int] = {}
        self._current = -1
        self._size = 0
        #: Chunks kept in each segment (a segment no chunk is kept in goes).
        self._held: Counter[int] = Counter()
        #: Bytes in the segment files.
        self.size = 0
        #: Called with a segment's number just after it is begun (the store writes its tables first).
        self.on_new_segment: Callable[[int], None] | None = None

    def path_of(self, segment: int) -> Path:
        return self.directory / _NAME.format(segment)

    def make_room(self, size: int) -> None:
        """Begin a new segment unless ``size`` more bytes fit in the newest (``OSError`` when
        the disk has not the room for one)."""
        with self._lock:
            if self._current < 0 or self._size + size > self.segment_bytes:
                self._begin()

    def append(self, kind: bytes, blob: bytes, *, hold: bool = True) -> tuple[int, int]:
        """Write ``blob`` at the end of the newest segment (begun first when there is none;
        ``make_room`` begins the next); its segment and offset. ``hold``: a chunk is kept in
        it (``release`` when it goes). ``OSError`` when it cannot be written (nothing of it
        stays)."""
        with self._lock:
            if self._current < 0:
                self._begin()
            segment, offset = self._current, self._size + _RECORD.size
            self._put(_RECORD.pack(kind, len(blob)) + blob)
            if hold:
                self._held[segment] += 1
            return segment, offset

    def _begin(self) -> None:
        free = _free_bytes(self.directory)
        if free is not None and free < self.min_free_bytes:
            raise OSError(errno.ENOSPC, f"less than {self.min_free_bytes >> 20} MB free on its disk")
        previous = self._current
        self._current += 1
        fd = os.open(self.path_of(self._current), os.O_RDWR | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o600)
        self._fds[self._current] = fd
        self._size = 0
        if previous >= 0 and not self._held[previous]:
            self._remove(previous)
        if self.on_new_segment is not None:
            self.on_new_segment(self._current)

    def _put(self, data: bytes) -> None:
        fd, start = self._fds[self._current], self._size
        view = memoryview(data)
        try:
            while view:
                written = self._write(fd, bytes(view[: 1 << 24]))
                if written <= 0:
                    raise OSError(errno.EIO, "nothing written")
                view = view[written:]
        except OSError:
            try:
                os.ftruncate(fd, start)  # whole or not at all
                os.lseek(fd, start, os.SEEK_SET)
            except OSError:
                pass
            raise
        self._size += len(data)
        self.size += len(data)

    def read(self, segment: int, offset: int, length: int) -> bytes:
        """The ``length`` bytes at ``offset`` of a segment (``OSError`` when they cannot be read)."""
        fd = self._fds.get(segment)
        if fd is None:
            raise OSError(errno.ENOENT, f"segment {segment} is gone")
        data = os.pread(fd, length, offset)
        if len(data) != length:
            raise OSError(errno.EIO, f"segment {segment} is shorter than its index says")
        return data

    def release(self, segment: int) -> None:
        """A chunk of ``segment`` is no longer kept; the file goes with its last chunk."""
        with self._lock:
            self._held[segment] -= 1
            if self._held[segment] <= 0 and segment != self._current:
                self._remove(segment)

    def _remove(self, segment: int) -> None:
        del self._held[segment]
        fd = self._fds.pop(segment, None)
        if fd is not None:
            os.close(fd)
        path = self.path_of(segment)
        try:
            self.size -= path.stat().st_size
            path.unlink()
        except OSError:
            pass

    def segments(self) -> list[int]:
        return sorted(self._fds)

    def close(self) -> None:
        """Close every segment (the files stay: the caller removes the directory, or keeps it)."""
        with self._lock:
            for fd in self._fds.values():
                os.close(fd)
            self._fds.clear()


def records_of(path: Path) -> Iterator[tuple[bytes, int, bytes]]:
    """A segment file's records: kind, the blob's offset, the blob (stops at a cut-off one)."""
    data = path.read_bytes()
    at = 0
    while at + _RECORD.size <= len(data):
        kind, length = _RECORD.unpack_from(data, at)
        start = at + _RECORD.size
        if start + length > len(data):
            return
        yield kind, start, data[start : start + length]
        at = start + length


def pack_kept(chunks: list[tuple[int, int]], skip: int) -> bytes:
    """A ``KEPT`` record's blob: the segment and blob offset of each chunk the store still
    held, oldest first, and how many of the first one's records it had dropped already."""
    return _KEPT_HEAD.pack(skip) + b"".join(_KEPT_CHUNK.pack(segment, offset) for segment, offset in chunks)


def unpack_kept(blob: bytes) -> dict[tuple[int, int], int]:
    """Each chunk ``pack_kept`` names, as (segment, offset), to the records to skip at its start."""
    (skip,) = _KEPT_HEAD.unpack_from(blob)
    chunks = list(_KEPT_CHUNK.iter_unpack(blob[_KEPT_HEAD.size :]))
    return {chunk: skip if number == 0 else 0 for number, chunk in enumerate(chunks)}


def _free_bytes(directory: Path) -> int | None:
    try:
        info = os.statvfs(directory)
    except OSError:
        return None
    return info.f_bavail * info.f_frsize
