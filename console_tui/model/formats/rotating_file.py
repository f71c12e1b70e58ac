"""A log file that is appended to, rotated by size, and keeps a number of old files.

As ROS 1's rosout does it: when ``rosout.log`` would grow past ``max_bytes`` it becomes
``rosout.log.1`` (``.1`` becomes ``.2`` and so on, the one past ``keep`` is removed) and a
new ``rosout.log`` starts with the header. Writes are buffered (here, by line);
``flush`` hands them to the operating system, so a process killed at any moment loses
only what was written since the last ``flush``. Failing writes (a full disk, a removed
directory) never raise: the lines not written whole are counted in ``lost`` (and those
written in ``written``: one count each, exact), the failure is described in ``error``,
and the file is opened again on a later write. A line cut by the failure is counted lost
and the next write starts on a fresh line, so it is never glued to the cut one. Only a
regular file is written to: a FIFO or a device in its place is refused, never waited on.
"""

from __future__ import annotations

import os
import stat
import time
from pathlib import Path

#: After a failure, how long to wait before trying to open the file again.
RETRY_S = 5.0
#: Buffered bytes past which a write hands them to the operating system at once.
BUFFER_BYTES = 1 << 16


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
        #: Lines that could not be written (whole).
        self.lost = 0
        #: Lines handed to the operating system whole.
        self.written = 0
        #: The last failure, or "".
        self.error = ""
        #: How many times the file was rotated.
        self.rotations = 0
        self._fd: int | None = None
        #: Lines written but not yet handed on, each encoded.
        self._pending: list[bytes] = []
        self._pending_bytes = 0
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
            # Non-blocking: a FIFO without a reader fails at once instead of hanging.
            fd = os.open(self.path, os.O_RDWR | os.O_APPEND | os.O_CREAT | os.O_NONBLOCK | os.O_CLOEXEC, 0o644)
            info = os.fstat(fd)
            if not stat.S_ISREG(info.st_mode):
                os.close(fd)
                raise OSError(0, "not a regular file")
            self._fd = fd
            self.size = info.st_size
            if self.size == 0 and self.header:
                self._write_out(self.header)
                self.size = len(self.header)
            elif self.size and not self._ends_a_line(fd):
                self._write_out(b"\n")  # after a cut line: the next one starts on a line of its own
                self.size += 1
            self.error = ""
        except OSError as error:
            self._failed(error)

    def _ends_a_line(self, fd: int) -> bool:
        return os.pread(fd, 1, self.size - 1) == b"\n"

    def _write_out(self, data: bytes) -> int:
        """Write ``data`` to the file; how much of it went out before a failure (``OSError``
        carries it as ``written``)."""
        assert self._fd is not None
        view = memoryview(data)
        done = 0
        while done < len(data):
            try:
                done += os.write(self._fd, view[done:])
            except OSError as error:
                error.written = done  # type: ignore[attr-defined]
                raise
        return done

    def _failed(self, error: OSError) -> None:
        self.error = f"{self.path}: {error.strerror or error}"
        self._retry_at = time.monotonic() + RETRY_S
        self.lost += len(self._pending)
        self._pending.clear()
        self._pending_bytes = 0
        self._drop_file()

    def _drop_file(self) -> None:
        """Close the file if it is open; a failure to close is let pass."""
        if self._fd is not None:
            try:
                os.close(self._fd)
            except OSError:
                pass
            self._fd = None

    def write(self, lines: list[str]) -> None:
        """Append ``lines`` (each with its newline), rotating first when they do not fit."""
        if not lines:
            return
        if self._fd is None:
            if time.monotonic() < self._retry_at:
                self.lost += len(lines)
                return
            self._open(existing=True)
            if self._fd is None:
                self.lost += len(lines)
                return
        encoded = [line.encode("utf-8", "replace") for line in lines]
        size = sum(len(line) for line in encoded)
        if self.size + size > self.max_bytes and self.size > len(self.header):
            if len(lines) > 1 and size > self.max_bytes // 2:
                half = len(lines) // 2  # a large batch: rotate at a line boundary in it
                self.write(lines[:half])
                self.write(lines[half:])
                return
            self.rotate()
            if self._fd is None:
                self.lost += len(lines)
                return
        self._pending.extend(encoded)
        self._pending_bytes += size
        self.size += size
        if self._pending_bytes >= BUFFER_BYTES:
            self.flush()

    def _hand_on(self) -> None:
        """The buffered lines to the file; on a failure, those not written whole are lost."""
        if self._fd is None or not self._pending:
            return
        lines, self._pending, self._pending_bytes = self._pending, [], 0
        try:
            self._write_out(b"".join(lines))
        except OSError as error:
            done = getattr(error, "written", 0)
            whole = 0
            for line in lines:
                if done < len(line):
                    break
                done -= len(line)
                whole += 1
            self.written += whole
            self.lost += len(lines) - whole
            self._failed(error)
            return
        self.written += len(lines)

    def rotate(self) -> None:
        """Start a new file now: the current one becomes ``.1``."""
        self._hand_on()
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
        self._hand_on()

    def close(self) -> None:
        self._hand_on()
        if self._fd is not None:
            try:
                os.close(self._fd)
            except OSError as error:
                self.error = f"{self.path}: {error.strerror or error}"
            self._fd = None

    def files(self) -> list[Path]:
        """The files on disk, oldest first: ``path.keep`` ... ``path.1``, ``path``."""
        found = [Path(f"{self.path}.{n}") for n in range(self.keep, 0, -1)]
        return [p for p in [*found, self.path] if p.exists()]
