"""Following text log files as they grow, as ``tail -F`` does: records appended later,
and the new file when one is rotated (renamed and started again) or truncated.

What the file holds when following starts is read in one go by the format's reader, up
to its last whole line (after its rotated files, when it was opened with them: only the
newest file is followed). After that only whole lines are read. A record can span lines
(multi-line messages), so new lines are read into records when the file has been quiet
for one look, or when ``HOLD_S`` has passed or ``HOLD_BYTES`` have gathered: a writer
that writes each record at once (as ``console-tui rosout`` and rcl's log files do) does
not have a record cut in two.
"""

from __future__ import annotations

import io
import os
import time
from collections.abc import Iterator
from typing import BinaryIO, cast

from ...model.formats import Problems, TextFormat, TextLines, read_batches
from ...model.store.record import LogRecord
from .log_file import TextLogFile
from .rotated import PartsStream

#: Most bytes read in one look at a file.
READ_BYTES = 1 << 20
#: Whole lines held back at most this long (or this many bytes) waiting for a quiet look.
HOLD_S = 0.5
HOLD_BYTES = 256 * 1024


class FollowedFile:
    """One text log file, read from its start and then followed.

    ``read()`` returns the records of the lines that came since the last call (maybe
    none). ``at_end`` says whether the last look reached the end of the file.
    Problems (bad lines, a file that went away) go to ``problems``.
    """

    def __init__(self, log_file: TextLogFile) -> None:
        self.path = log_file.path
        #: Rotated files opened with it (oldest first): read once, before it.
        self.older = [part for part in log_file.parts if part != log_file.path]
        self.format: TextFormat = log_file.format
        self.source = log_file.source
        self.problems: Problems = log_file.problems
        self.at_end = False
        self._stream: io.BufferedReader | None = None
        self._inode = -1
        self._offset = 0
        self._partial = b""
        self._held: list[bytes] = []
        self._held_bytes = 0
        self._held_since = 0.0
        self._line = 1
        self._open()

    def _open(self) -> None:
        try:
            stream = open(self.path, "rb")
        except OSError:
            self._stream = None
            return
        self._stream = stream
        self._inode = os.fstat(stream.fileno()).st_ino
        self._offset = 0
        self._line = 1

    def close(self) -> None:
        if self._stream is not None:
            self._stream.close()
            self._stream = None

    def read(self, *, now: float | None = None) -> list[LogRecord]:
        """Records of what was appended since the last call (at most ``READ_BYTES`` of it)."""
        now = time.monotonic() if now is None else now
        if self._stream is None:
            self._open()
            if self._stream is None:
                return []
        data = self._stream.read(READ_BYTES)
        self._offset += len(data)
        self.at_end = len(data) < READ_BYTES
        replaced = self.at_end and self._replaced()
        if data:
            complete = (self._partial + data).rsplit(b"\n", 1)
            if len(complete) == 2:
                self._hold(complete[0] + b"\n", now)
                self._partial = complete[1]
            else:
                self._partial = complete[0]
        quiet = not data
        records: list[LogRecord] = []
        if self._held and (quiet or replaced or self._held_bytes >= HOLD_BYTES or now - self._held_since >= HOLD_S):
            records = self._parse()
        if replaced:
            if self._partial:  # the old file's last line never got its newline
                self._hold(self._partial + b"\n", now)
                self._partial = b""
                records += self._parse()
            self.close()
            self._open()
        return records

    def _hold(self, lines: bytes, now: float) -> None:
        if not self._held:
            self._held_since = now
        self._held.append(lines)
        self._held_bytes += len(lines)

    def _parse(self) -> list[LogRecord]:
        data = b"".join(self._held)
        self._held.clear()
        self._held_bytes = 0
        lines = _LinesFrom(data, self._line, self.problems)
        records = list(self.format.records(lines, self.source, self.problems))
        self._line += data.count(b"\n")
        return records

    def _replaced(self) -> bool:
        """The path now names another file (rotated), or the file got shorter (truncated)."""
        try:
            info = os.stat(self.path)
        except OSError:
            return False  # gone for now (between a rename and the new file): keep reading the old one
        return info.st_ino != self._inode or info.st_size < self._offset

    def records_so_far(self) -> Iterator[list[LogRecord]]:
        """The records of the file's whole lines as they are now, in batches; ``read()``
        carries on after them. Call it first, once."""
        stream = self._stream
        if stream is None:
            return
        end = _last_line_end(stream)
        readable = _Bounded(stream, end)
        older = PartsStream(self.older) if self.older else None
        lines = TextLines(cast(BinaryIO, _Chain(older, readable) if older else readable), self.problems)
        try:
            yield from read_batches(stream, self.format, self.source, self.problems, lines=lines)
        finally:
            if older is not None:
                older.close()
        stream.seek(end)
        self._offset = end
        self._line = readable.newlines + 1


class _LinesFrom(TextLines):
    """The lines of ``data``, numbered from ``first_line``."""

    def __init__(self, data: bytes, first_line: int, problems: Problems) -> None:
        super().__init__(io.BytesIO(data), problems)
        self.first_line = first_line

    def __iter__(self) -> Iterator[tuple[int, str]]:
        shift = self.first_line - 1
        for number, text in super().__iter__():
            yield number + shift, text


def _last_line_end(stream: io.BufferedReader) -> int:
    """Where the file's last whole line ends (0 when it has none)."""
    end = os.fstat(stream.fileno()).st_size
    position = end
    while position > 0:
        start = max(0, position - 65536)
        stream.seek(start)
        block = stream.read(position - start)
        newline = block.rfind(b"\n")
        if newline >= 0:
            stream.seek(0)
            return start + newline + 1
        position = start
    stream.seek(0)
    return 0


class _Bounded(io.RawIOBase):
    """The first ``limit`` bytes of a stream (read from where it is)."""

    def __init__(self, stream: io.BufferedReader, limit: int) -> None:
        self._stream = stream
        self._left = limit
        #: Lines read so far.
        self.newlines = 0

    def readable(self) -> bool:
        return True

    def read(self, size: int = -1) -> bytes:
        if size < 0 or size > self._left:
            size = self._left
        data = self._stream.read(size)
        self._left -= len(data)
        self.newlines += data.count(b"\n")
        return data


class _Chain(io.RawIOBase):
    """One stream, then another."""

    def __init__(self, first: PartsStream, second: _Bounded) -> None:
        self._streams: list[PartsStream | _Bounded] = [first, second]

    def readable(self) -> bool:
        return True

    def read(self, size: int = -1) -> bytes:
        while self._streams:
            data = self._streams[0].read(size)
            if data:
                return data
            self._streams.pop(0)
        return b""
