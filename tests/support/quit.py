"""``console-tui`` run in a terminal (a pty) and ended with ``q``: the processes it started
while it ran, and whether they outlived it."""

from __future__ import annotations

import fcntl
import os
import pty
import select
import struct
import sys
import termios
import time
from pathlib import Path

from support.rosproc import PATIENCE_S


def children(pid: int) -> set[int]:
    """The children of ``pid``'s threads (a thread or the process that ends meanwhile: none)."""
    found: set[int] = set()
    try:
        tasks = list(Path(f"/proc/{pid}/task").iterdir())
    except OSError:
        return found
    for task in tasks:
        try:
            found.update(int(child) for child in (task / "children").read_text().split())
        except OSError:  # the thread ended between the listing and the read
            continue
    return found


def _cmdline(pid: int) -> bytes:
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ")
    except OSError:  # gone meanwhile
        return b""


def intake_children(pid: int) -> set[int]:
    return {child for child in children(pid) if b"intake_process" in _cmdline(child)}


def run_and_quit(env: dict[str, str], *args: str, others_expected: int = 0) -> tuple[set[int], set[int], int]:
    """``console-tui ARGS`` in a terminal; once it shows its table and has started its intake
    process (and ``others_expected`` other processes), ``q``. Returns the intake process(es)
    and the other children seen while it ran, and its exit status."""
    command = [str(Path(sys.executable).parent / "console-tui"), *args]
    pid, fd = pty.fork()
    if pid == 0:  # the child: becomes console-tui
        os.execve(command[0], command, {**env, "TERM": "xterm-256color"})
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 120, 0, 0))
    intake: set[int] = set()
    others: set[int] = set()
    seen = b""
    try:
        deadline = time.monotonic() + PATIENCE_S
        while time.monotonic() < deadline and not (intake and b"Message" in seen and len(others) >= others_expected):
            if select.select([fd], [], [], 0.1)[0]:
                seen += os.read(fd, 65536)
            intake = intake_children(pid)
            others = children(pid) - intake
        assert intake, "no intake process seen"
        time.sleep(1.0)
        os.write(fd, b"q")
        deadline = time.monotonic() + PATIENCE_S
        status = None
        while time.monotonic() < deadline:
            done, status = os.waitpid(pid, os.WNOHANG)
            if done:
                break
            if select.select([fd], [], [], 0.05)[0]:
                try:
                    os.read(fd, 65536)
                except OSError:
                    pass
        assert status is not None, "console-tui did not end after q"
    finally:
        try:
            os.kill(pid, 9)
            os.waitpid(pid, 0)
        except (ProcessLookupError, ChildProcessError):
            pass
        os.close(fd)
    return intake, others, os.waitstatus_to_exitcode(status)
