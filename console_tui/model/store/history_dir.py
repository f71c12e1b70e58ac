"""Directories for the history on disk: private to the user, or refused with the reason.

A session's spilled chunks go to a directory of its own, ``session-<pid>-<random>``, inside
the user's cache (``$XDG_CACHE_HOME/console-tui/history``, else
``~/.cache/console-tui/history``, or ``$CONSOLE_TUI_HISTORY_DIR``), removed when the session ends; one whose process is gone
(a session killed) is removed by the next start. Log messages are the robot's data: the
directory and the one above it must be real directories (no links), the user's, and
writable by nobody else; files are made 0600, directories 0700. A directory that is not so
is refused (``UnsafeDirectory``, saying why) and the history stays in memory.

A kept history (``--keep-history``) is a directory of its own (in the ROS log directory),
one ``kept-<time>-<pid>`` directory a session, kept when it ends and pruned to a bound, the
oldest segments first (``prune_kept``): a rotating history across sessions, as log_view has.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
import time
from pathlib import Path

from .chunk_spill import ChunkSpill
from .spill_file import SpillFiles

SESSION_PREFIX = "session-"
KEPT_PREFIX = "kept-"
#: A kept history holds at most this much, the oldest sessions' segments going first.
KEPT_BYTES = 100 << 20


class UnsafeDirectory(Exception):
    """A directory the history must not be written to; the message says why."""


#: Where sessions' histories go instead of the cache's folder (a bigger disk; each test its own).
DIRECTORY_VARIABLE = "CONSOLE_TUI_HISTORY_DIR"


def cache_base() -> Path:
    chosen = os.environ.get(DIRECTORY_VARIABLE)
    if chosen:
        return Path(chosen)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "console-tui" / "history"


def why_unsafe(path: Path, *, above: bool = False) -> str:
    """Why ``path`` must not hold the history, or "": it must be a real directory of this
    user's that no one else can write to. ``above``: the directory above the history's, which
    may also be a shared one with the sticky bit (``/tmp``: no one can take away or replace
    what is ours in it) of any owner."""
    try:
        info = os.lstat(path)
    except OSError as error:
        return f"{path}: {error.strerror or error}"
    if stat.S_ISLNK(info.st_mode):
        return f"{path} is a symbolic link"
    if not stat.S_ISDIR(info.st_mode):
        return f"{path} is not a directory"
    if above and info.st_mode & stat.S_ISVTX:
        return ""
    if info.st_uid != os.geteuid():
        return f"{path} belongs to another user (uid {info.st_uid})"
    if info.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        return f"{path} can be written by other users (mode {stat.S_IMODE(info.st_mode):o})"
    return ""


def private_directory(path: Path) -> Path:
    """``path``, made (0700) if it is not there, and checked with the directory above it
    (``UnsafeDirectory`` when either may not hold the history)."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        path.mkdir(exist_ok=True, mode=0o700)
    except OSError as error:
        raise UnsafeDirectory(f"cannot make {path}: {error.strerror or error}") from None
    for place, above in ((path.parent, True), (path, False)):
        reason = why_unsafe(place, above=above)
        if reason:
            raise UnsafeDirectory(reason)
    return path


def session_directory(base: Path | None = None) -> Path:
    """A new private directory for this session's history in ``base`` (the cache's by
    default), after removing those of sessions whose process is gone."""
    base = private_directory(base or cache_base())
    remove_stale_sessions(base)
    try:
        return Path(tempfile.mkdtemp(prefix=f"{SESSION_PREFIX}{os.getpid()}-", dir=base))  # mode 0700
    except OSError as error:
        raise UnsafeDirectory(f"cannot make a directory in {base}: {error.strerror or error}") from None


def kept_directory(base: Path) -> Path:
    """A new private directory for this session's kept history in ``base`` (pruned first:
    a session that was killed did not prune it)."""
    base = private_directory(base)
    now = time.time_ns()
    stamp = time.strftime("%Y%m%d-%H%M%S", time.localtime(now // 1_000_000_000)) + f".{now % 1_000_000_000:09d}"
    try:
        return Path(tempfile.mkdtemp(prefix=f"{KEPT_PREFIX}{stamp}-{os.getpid()}-", dir=base))
    except OSError as error:
        raise UnsafeDirectory(f"cannot make a directory in {base}: {error.strerror or error}") from None


def kept_sessions(base: Path) -> list[Path]:
    """The kept sessions' directories in ``base``, oldest first (their names begin with their time)."""
    try:
        entries = [Path(entry.path) for entry in os.scandir(base) if entry.name.startswith(KEPT_PREFIX)]
    except OSError:
        return []
    return sorted(path for path in entries if path.is_dir() and not path.is_symlink())


def prune_kept(base: Path, bound: int = KEPT_BYTES, *, keep: Path | None = None) -> int:
    """Remove the oldest segment files of the kept sessions in ``base`` until they hold at most
    ``bound`` bytes (never from ``keep``'s while it is being written); the bytes left."""
    segments = []
    for session in kept_sessions(base):
        for path in sorted(session.glob("segment-*.ctc")):
            try:
                segments.append((session, path, path.stat().st_size))
            except OSError:
                pass
    total = sum(size for _, _, size in segments)
    for session, path, size in segments:
        if total <= bound:
            break
        if session == keep:
            continue
        try:
            path.unlink()
            total -= size
        except OSError:
            pass
    for session in kept_sessions(base):
        if session != keep and not any(session.iterdir()):
            session.rmdir()
    return total


def remove_stale_sessions(base: Path) -> None:
    """Remove the session directories in ``base`` whose process has ended."""
    try:
        entries = list(os.scandir(base))
    except OSError:
        return
    for entry in entries:
        pid = _pid_of(entry.name)
        if pid is None or pid == os.getpid() or _alive(pid):
            continue
        try:
            if entry.is_dir(follow_symlinks=False) and entry.stat(follow_symlinks=False).st_uid == os.geteuid():
                shutil.rmtree(entry.path, ignore_errors=True)
        except OSError:
            pass


def remove_directory(path: Path) -> None:
    shutil.rmtree(path, ignore_errors=True)


def _pid_of(name: str) -> int | None:
    if not name.startswith(SESSION_PREFIX):
        return None
    number = name[len(SESSION_PREFIX) :].split("-", 1)[0]
    return int(number) if number.isdigit() else None


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True  # someone else's: not ours to judge
    return True


def open_session_spill(base: Path | None = None) -> tuple[ChunkSpill | None, Path | None, str]:
    """A spill for this session's history in a new private directory: the spill, its
    directory and ""; or None, None and why the history stays in memory."""
    try:
        directory = session_directory(base)
    except UnsafeDirectory as error:
        return None, None, str(error)
    return ChunkSpill(SpillFiles(directory)), directory, ""


def open_kept_spill(base: Path) -> tuple[ChunkSpill | None, Path | None, str]:
    """A spill whose history is kept in a new session directory of ``base``; as
    ``open_session_spill``."""
    try:
        directory = kept_directory(base)
    except UnsafeDirectory as error:
        return None, None, str(error)
    prune_kept(base, keep=directory)
    spill = ChunkSpill(SpillFiles(directory), keep=True)
    return spill, directory, ""


def close_spill(spill: ChunkSpill, directory: Path, *, bound: int = KEPT_BYTES) -> None:
    """The session ends: its files closed, and its directory removed, or, kept, the kept
    history pruned to ``bound`` (the oldest segments go first)."""
    spill.files.close()
    if not spill.keep:
        remove_directory(directory)
    else:
        prune_kept(directory.parent, bound)
