"""A log file that is appended to, rotated by size, and keeps a number of old files.

As ROS 1's rosout does it: when ``rosout.log`` would grow past ``max_bytes`` it becomes
``rosout.log.1`` (``.1`` becomes ``.2`` and so on, the one past ``keep`` is removed) and a
new ``rosout.log`` starts with the header. Writes are buffered; ``flush`` hands them to
the operating system, so a process killed at any moment loses only what was written
since the last ``flush``. Failing writes (a full disk, a removed directory) never raise:
they are counted in ``lost`` and described in ``error``, and the file is opened again
on a later write.
"""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import BinaryIO

#: After a failure, how long to wait before trying to open the file again.
RETRY_S = 5.0


class RotatingFile:
    """Appends text to ``path``; see the module docstring.

    ``header`` starts every new file (and an existing file that does not start with it
    is rotated away first, so one file never mixes formats). ``keep`` is the number of
    rotated files kept (0: none, the full file is removed).
    """

    def __init__(self, path: str | os.PathLike[str], *, max_bytes: int, keep: int, header: str = "") -> None:
        if max_bytes < 1 or keep < 0:
            raise ValueError("max_bytes must be at least 1 and keep at least 0")
        self.path = Path(path)
        self.max_bytes = max_bytes
        self.keep = keep
        self.header = header.encode("utf-8")
        self.size = 0
        #: Lines that could not be written.
        self.lost = 0
        #: The last failure, or "".
        self.error = ""
        #: How many times the file was rotated.
        self.rotations = 0
        self._file: BinaryIO | None = None
        self._retry_at = 0.0
        self._open(existing=True)

    def _open(self, *, existing: bool = False) -> None:
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            if existing and self.path.exists() and self.path.stat().st_size > 0:
                with open(self.path, "rb") as old:
                    ours = old.read(len(self.header)) == self.header if self.header else True
                if not ours:
                    self._shift()
            self._file = open(self.path, "ab")
            self.size = self._file.tell()
            if self.size == 0 and self.header:
                self._file.write(self.header)
                self.size = len(self.header)
            self.error = ""
        except OSError as error:
            self._failed(error)

    def _failed(self, error: OSError) -> None:
        self.error = f"{self.path}: {error.strerror or error}"
        self._retry_at = time.monotonic() + RETRY_S
        self._drop_file()

    def _drop_file(self) -> None:
        """Close the file if it is open; a failure to close is let pass."""
        if self._file is not None:
            try:
                self._file.close()
            except OSError:
                pass
            self._file = None

    def write(self, lines: list[str]) -> None:
        """Append ``lines`` (each with its newline), rotating first when they do not fit."""
        if not lines:
            return
        if self._file is None:
            if time.monotonic() < self._retry_at:
                self.lost += len(lines)
                return
            self._open(existing=True)
            if self._file is None:
                self.lost += len(lines)
                return
        data = "".join(lines).encode("utf-8", "replace")
        if self.size + len(data) > self.max_bytes and self.size > len(self.header):
            if len(lines) > 1 and len(data) > self.max_bytes // 2:
                half = len(lines) // 2  # a large batch: rotate at a line boundary in it
                self.write(lines[:half])
                self.write(lines[half:])
                return
            self.rotate()
            if self._file is None:
                self.lost += len(lines)
                return
        try:
            self._file.write(data)
            self.size += len(data)
        except OSError as error:
            self.lost += len(lines)
            self._failed(error)

    def rotate(self) -> None:
        """Start a new file now: the current one becomes ``.1``."""
        self._drop_file()
        try:
            self._shift()
        except OSError as error:
            self._failed(error)
            return
        self.rotations += 1
        self._open()

    def _shift(self) -> None:
        """``path.N-1`` to ``path.N`` ... ``path`` to ``path.1``; what falls past ``keep`` goes."""
        base = str(self.path)
        if self.keep == 0:
            os.unlink(base)
            return
        oldest = f"{base}.{self.keep}"
        if os.path.lexists(oldest):
            os.unlink(oldest)
        for number in range(self.keep - 1, 0, -1):
            older = f"{base}.{number}"
            if os.path.lexists(older):
                os.replace(older, f"{base}.{number + 1}")
        os.replace(base, f"{base}.1")

    def flush(self) -> None:
        """Hand what was written to the operating system."""
        if self._file is not None:
            try:
                self._file.flush()
            except OSError as error:
                self._failed(error)

    def close(self) -> None:
        if self._file is not None:
            try:
                self._file.close()
            except OSError as error:
                self.error = f"{self.path}: {error.strerror or error}"
            self._file = None

    def files(self) -> list[Path]:
        """The files on disk, oldest first: ``path.keep`` ... ``path.1``, ``path``."""
        found = [Path(f"{self.path}.{n}") for n in range(self.keep, 0, -1)]
        return [p for p in [*found, self.path] if p.exists()]
