"""``journalctl -o json`` as a process: what to ask it (``JournalQuery``), and its lines, bounded.

Why journalctl and not the journal's library: python-systemd is the distribution's package for
its own Python (on PyPI a source package that needs libsystemd's headers and a compiler), and
``sd_journal`` through ctypes would parse journal files in the console's process, files that
may come from any robot of a fleet: a damaged one that crashes the reader would take the
console with it. journalctl reads every file version and compression the machine's systemd
writes, with the user's permissions (and says when they hide entries), in a process of its own;
what it prints is read a line at a time, each line at most ``MAX_LINE_BYTES`` (the rest of a
longer line is dropped and counted), and it is killed when reading ends.

Without journalctl (no systemd on this machine) ``JournalUnavailable`` says so; so it does
for this machine's journal when there is none (no journal files and no journald socket).
"""

from __future__ import annotations

import os
import selectors
import shutil
import subprocess
from collections import deque
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from ...model.formats.journal_entry import FIELDS, MAX_ENTRY_BYTES

#: Where the system's journal lives: persistent, and in memory (``Storage=volatile``).
JOURNAL_DIRECTORIES = (Path("/var/log/journal"), Path("/run/log/journal"))
#: journald's socket: there while journald runs.
JOURNALD_SOCKET = Path("/run/systemd/journal/socket")
#: A line of journalctl's output longer than this is not read (``MAX_ENTRY_BYTES``).
MAX_LINE_BYTES = MAX_ENTRY_BYTES
#: The entries of this machine's journal shown before following it, without ``--since``.
DEFAULT_LINES = 1000
#: How long ``close`` waits for journalctl after SIGTERM before killing it.
STOP_WAIT_S = 0.5
READ_BYTES = 1 << 16


class JournalUnavailable(Exception):
    """There is no journal to read here (no journalctl, no journal): what to do, in words."""


@dataclass(frozen=True)
class JournalQuery:
    """What to read of the journal: this machine's (no ``files``, no ``directory``), some journal
    files, or a directory of them; only ``units`` (any of them) if given; from ``since``
    (journalctl's time: ``2026-12-06 10:00``, ``yesterday``, ``-1h``) or, following this
    machine's journal without it, its last ``DEFAULT_LINES`` entries (files and directories:
    all they hold); then, with ``follow``, what comes."""

    files: tuple[str, ...] = ()
    directory: str = ""
    units: tuple[str, ...] = ()
    since: str = ""
    follow: bool = False

    @property
    def local(self) -> bool:
        return not self.files and not self.directory

    def arguments(self) -> list[str]:
        """journalctl's arguments (without the program)."""
        args = ["-o", "json", "--no-pager", "-q", f"--output-fields={','.join(FIELDS)}"]
        args += [f"--file={name}" for name in self.files]
        if self.directory:
            args.append(f"--directory={self.directory}")
        args += [f"--unit={unit}" for unit in self.units]
        if self.since:
            args.append(f"--since={self.since}")
        elif self.follow and self.local:
            args.append(f"--lines={DEFAULT_LINES}")
        elif self.follow:  # a journal file or directory: all of it, then what comes
            args.append("--no-tail")
        if self.follow:
            args.append("--follow")
        return args

    def describe(self) -> str:
        """What it reads, in words: ``this machine's journal (nav.service)``."""
        if self.files:
            where = ", ".join(Path(name).name for name in self.files)
        elif self.directory:
            where = f"the journal in {self.directory}"
        else:
            where = "this machine's journal"
        units = f" ({', '.join(self.units)})" if self.units else ""
        since = f" since {self.since}" if self.since else ""
        return f"{where}{units}{since}"


def find_journalctl() -> str:
    """journalctl's path; ``JournalUnavailable`` when this machine has none."""
    found = shutil.which("journalctl") or next(
        (name for name in ("/usr/bin/journalctl", "/bin/journalctl") if os.access(name, os.X_OK)), None
    )
    if found is None:
        raise JournalUnavailable(
            "the systemd journal cannot be read here: journalctl is not installed (this machine has no "
            "systemd; on Debian and Ubuntu it comes with the package systemd)"
        )
    return found


def local_journal_problem() -> str:
    """Why this machine's journal cannot be read (no journald and no journal files), or ""."""
    if JOURNALD_SOCKET.exists():
        return ""
    for directory in JOURNAL_DIRECTORIES:
        try:
            if any(directory.glob("*.journal")) or any(directory.glob("*/*.journal")):
                return ""
        except OSError:
            continue
    return (
        "this machine has no systemd journal: journald is not running (no /run/systemd/journal/socket) "
        "and /var/log/journal and /run/log/journal hold no journal files"
    )


class Journalctl:
    """journalctl running a query: ``lines()`` gives what it prints, ``close()`` ends it."""

    def __init__(self, query: JournalQuery) -> None:
        self.query = query
        #: Lines over ``MAX_LINE_BYTES`` dropped.
        self.too_long = 0
        #: journalctl's last lines on stderr (its complaints and hints).
        self.stderr: deque[str] = deque(maxlen=10)
        command = [find_journalctl(), *query.arguments()]
        try:
            self.process = subprocess.Popen(
                command,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                start_new_session=True,  # the terminal's Ctrl+C is the console's; it ends journalctl
            )
        except OSError as error:
            raise JournalUnavailable(f"journalctl could not start: {error.strerror or error}") from None

    def lines(self, pause_s: float | None = None) -> Iterator[bytes | None]:
        """Each line journalctl prints (without its newline), until it ends; with ``pause_s``,
        ``None`` whenever nothing came for that long (the reader may hand on what it has)."""
        process = self.process
        assert process.stdout is not None and process.stderr is not None
        out, err = process.stdout.fileno(), process.stderr.fileno()
        selector = selectors.DefaultSelector()
        selector.register(out, selectors.EVENT_READ)
        selector.register(err, selectors.EVENT_READ)
        pending = bytearray()
        skipping = False
        open_streams = 2
        try:
            while open_streams:
                ready = selector.select(pause_s)
                if not ready:
                    yield None
                    continue
                for key, _ in ready:
                    chunk = os.read(key.fd, READ_BYTES)
                    if not chunk:
                        selector.unregister(key.fd)
                        open_streams -= 1
                        continue
                    if key.fd == err:
                        self._complaints(chunk)
                        continue
                    pending += chunk
                    start = 0
                    while (end := pending.find(b"\n", start)) >= 0:
                        if skipping:
                            skipping = False
                        elif end - start <= MAX_LINE_BYTES:
                            yield bytes(pending[start:end])
                        else:
                            self.too_long += 1
                        start = end + 1
                    del pending[:start]
                    if len(pending) > MAX_LINE_BYTES:  # a line without end in sight: the rest of it goes
                        if not skipping:
                            self.too_long += 1
                        skipping = True
                        pending.clear()
            if pending and not skipping:
                yield bytes(pending)
        finally:
            selector.close()

    def _complaints(self, chunk: bytes) -> None:
        for line in chunk.decode("utf-8", "replace").splitlines():
            if line.strip():
                self.stderr.append(line.strip()[:500])

    def exit_status(self) -> int | None:
        return self.process.poll()

    def problem(self) -> str:
        """Why journalctl ended without reading (its exit status and last words), or ""."""
        code = self.process.wait()
        if code == 0:
            return ""
        words = f": {self.stderr[-1]}" if self.stderr else ""
        return f"journalctl failed (exit status {code}){words}"

    def close(self) -> None:
        """End journalctl (SIGTERM, then SIGKILL after ``STOP_WAIT_S``); safe to call twice."""
        process = self.process
        if process.poll() is None:
            process.terminate()
            try:
                process.wait(STOP_WAIT_S)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        for stream in (process.stdout, process.stderr):
            if stream is not None:
                stream.close()
