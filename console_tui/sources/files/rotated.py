"""A log and its rotated files read as one stream (``x.log.2``, ``x.log.1``, ``x.log``).

A file rotation may fall inside a record (a message that continues on the next lines, a
file cut by ``logrotate``): read as one stream, such a record comes back whole. Problems
still name the file and the line in it where they were found.
"""

from __future__ import annotations

import bisect
from collections.abc import Sequence
from pathlib import Path
from typing import BinaryIO

from ...model.formats import Problem, Problems


class PartsStream:
    """The bytes of several files, one after the other, as one binary stream to read.

    A part that does not end with a newline gets one, so its last line does not run on
    into the next file. ``starts`` tells where each part began: its first line and byte.
    """

    def __init__(self, parts: Sequence[Path]) -> None:
        self.parts = list(parts)
        self._index = 0
        self._current: BinaryIO | None = None
        self._last = b"\n"
        self._lines = 0
        self._offset = 0
        #: ``(first line number, first byte offset)`` of each part opened so far.
        self.starts: list[tuple[int, int]] = []

    def read(self, size: int = -1) -> bytes:
        while self._index < len(self.parts):
            if self._current is None:
                self._current = open(self.parts[self._index], "rb")
                self.starts.append((self._lines + 1, self._offset))
            data = self._current.read(size if size > 0 else -1)
            if data:
                self._lines += data.count(b"\n")
                self._offset += len(data)
                self._last = data[-1:]
                return data
            self._current.close()
            self._current = None
            self._index += 1
            if self._last != b"\n" and self._index < len(self.parts):
                self._last = b"\n"
                self._lines += 1
                self._offset += 1
                return b"\n"
        return b""

    def close(self) -> None:
        if self._current is not None:
            self._current.close()
            self._current = None

    def __enter__(self) -> PartsStream:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class PartsProblems(Problems):
    """Problems of a stream of parts, each told in terms of its own file and line."""

    def __init__(self, source: str, parts: Sequence[Path]) -> None:
        super().__init__(source)
        self.part_names = [path.name for path in parts]
        self.stream: PartsStream | None = None

    def add(self, what: str, *, line: int | None = None, offset: int | None = None) -> None:
        stream = self.stream
        if stream is None or not stream.starts or (line is None and offset is None):
            super().add(what, line=line, offset=offset)
            return
        if line is not None:
            index = max(bisect.bisect_right([first for first, _ in stream.starts], line) - 1, 0)
        else:
            assert offset is not None
            index = max(bisect.bisect_right([first for _, first in stream.starts], offset) - 1, 0)
        first_line, first_byte = stream.starts[index]
        if line is not None:
            line = line - first_line + 1
        if offset is not None:
            offset = offset - first_byte
        if len(self.items) >= self.limit:
            self.omitted += 1
            return
        folder, _, _ = self.source.rpartition("/")
        part = self.part_names[index]
        self.items.append(Problem(f"{folder}/{part}" if folder else part, what, line, offset))
