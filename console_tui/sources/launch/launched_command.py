"""A launch command run as its own terminal would run it: in a process group of its own, its
output read from a pseudo-terminal, stopped with SIGINT to the group, then escalated.

On a terminal, ``roslaunch`` and ``ros2 launch`` and their nodes write to the terminal: a
program writing to a terminal flushes each line (C's stdio, Python's ``print``), colours
what it prints, and gets Ctrl+C as SIGINT sent to its whole process group. Here the command's
standard output and error are the slave side of a pseudo-terminal whose master this process
reads, so they behave as they do at a terminal; the command runs in a session (and process
group) of its own, so the console's own Ctrl+C does not reach it, and ``stop()`` does what a
terminal's Ctrl+C does: SIGINT to the group, and then, for what is still running after
``SIGINT_WAIT_S``, SIGTERM, and after ``SIGTERM_WAIT_S`` more, SIGKILL, until no process of
the group is left. ``PYTHONUNBUFFERED=1`` is set unless the environment says otherwise, so a
Python node writing to a file (roslaunch's ``output="log"``) flushes each line as it would
on a terminal.

Lines are read up to ``MAX_LINE_CHARS`` (the rest of a longer line goes, said in the line);
text is decoded as UTF-8, what is not as stand-ins.
"""

from __future__ import annotations

import errno
import fcntl
import os
import select
import signal
import struct
import subprocess
import termios
import time
from collections.abc import Callable, Iterator, Mapping, Sequence

#: The terminal's size the command sees.
COLUMNS, ROWS = 200, 50
#: A line longer than this is cut (a runaway binary dump must not fill memory).
MAX_LINE_CHARS = 64 * 1024
#: After SIGINT to the group, how long until SIGTERM; after that, until SIGKILL.
SIGINT_WAIT_S = 10.0
SIGTERM_WAIT_S = 3.0
READ_BYTES = 1 << 16


class LaunchFailed(Exception):
    """The command could not be started (not found, not executable)."""


class LaunchedCommand:
    """``argv`` running under a pseudo-terminal (``lines``, ``stop``, ``exit_status``)."""

    def __init__(self, argv: Sequence[str], env: Mapping[str, str] | None = None) -> None:
        environment = dict(os.environ if env is None else env)
        environment.setdefault("PYTHONUNBUFFERED", "1")
        self.argv = list(argv)
        master, slave = os.openpty()
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", ROWS, COLUMNS, 0, 0))
        try:
            self.process = subprocess.Popen(
                self.argv,
                stdin=subprocess.DEVNULL,
                stdout=slave,
                stderr=slave,
                env=environment,
                start_new_session=True,
                close_fds=True,
            )
        except OSError as error:
            os.close(master)
            raise LaunchFailed(f"{self.argv[0]}: {error.strerror or error}") from None
        finally:
            os.close(slave)
        self._master = master
        self.pid = self.process.pid
        self._stopped = False
        #: ``lines`` has begun: the terminal is its to close.
        self._reading = False

    def lines(self, pause_s: float) -> Iterator[str | None]:
        """Each line the command prints (without its line end), until every process that
        holds the terminal has ended; ``None`` whenever nothing came for ``pause_s``."""
        master = self._master
        self._reading = True
        try:
            yield from self._read(master, pause_s)
        finally:
            os.close(master)

    def _read(self, master: int, pause_s: float) -> Iterator[str | None]:
        pending = bytearray()
        cut = False
        while True:
            ready, _, _ = select.select([master], [], [], pause_s)
            if not ready:
                yield None
                continue
            try:
                chunk = os.read(master, READ_BYTES)
            except OSError as error:  # EIO: the last writer closed the terminal
                if error.errno not in (errno.EIO, errno.EBADF):
                    raise
                chunk = b""
            if not chunk:
                break
            pending += chunk
            *complete, rest = pending.split(b"\n")
            for line in complete:
                if cut:  # the end of a line cut already
                    cut = False
                    continue
                yield _text(line) if len(line) <= MAX_LINE_CHARS else _cut(line)
            pending = bytearray(rest)
            if len(pending) > MAX_LINE_CHARS:  # a line without end: what came of it, cut
                yield _cut(pending)
                pending.clear()
                cut = True
        if pending and not cut:
            yield _text(pending)

    def exit_status(self) -> int | None:
        return self.process.poll()

    def stop(self, say: Callable[[str], None] | None = None) -> int:
        """End the command as its terminal's Ctrl+C would, and whatever of its group lingers
        after it; its exit status. ``say`` hears each escalation. Safe to call twice."""
        if not self._stopped:
            self._stopped = True
            group = self.pid
            before = ""
            for sig, wait in ((signal.SIGINT, SIGINT_WAIT_S), (signal.SIGTERM, SIGTERM_WAIT_S), (signal.SIGKILL, 5.0)):
                if not self._group_alive():
                    break
                name = signal.Signals(sig).name
                if before and say is not None:
                    say(f"the launch still runs {before}: {name} to its processes")
                _signal_group(group, sig)
                self._wait_group(wait)
                before = f"{wait:g} s after {name}"
        code = self.process.wait()
        if not self._reading:
            self._reading = True
            os.close(self._master)
        return code

    def _group_alive(self) -> bool:
        """Whether any process of the command's group is left (the command itself reaped)."""
        self.process.poll()
        return bool(group_members(self.pid))

    def _wait_group(self, seconds: float) -> None:
        deadline = time.monotonic() + seconds
        delay = 0.01
        while self._group_alive() and time.monotonic() < deadline:
            time.sleep(delay)
            delay = min(delay * 2, 0.1)


def group_members(group: int) -> list[int]:
    """The processes of process group ``group`` still running (zombies, which no signal
    ends, left out), from /proc; where there is none, whether ``killpg`` finds any."""
    try:
        entries = os.listdir("/proc")
    except OSError:
        try:
            os.killpg(group, 0)
        except ProcessLookupError:
            return []
        except PermissionError:
            pass
        return [group]
    members = []
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", encoding="ascii", errors="replace") as stat:
                fields = stat.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == group and fields[0] != "Z":  # (state, ppid, pgrp, ...)
            members.append(int(entry))
    return members


def _signal_group(group: int, sig: int) -> None:
    try:
        os.killpg(group, sig)
    except (ProcessLookupError, PermissionError):
        pass


def _cut(data: bytes | bytearray) -> str:
    return _text(data[:MAX_LINE_CHARS]) + " … [cut: the line went on]"


def _text(data: bytes | bytearray) -> str:
    return bytes(data).decode("utf-8", "replace").rstrip("\r")
