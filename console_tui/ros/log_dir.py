"""The ROS log directory: where it is, the runs it holds, and removing runs safely.

ROS 2 (rcl_logging) and ROS 1 (rospkg, roslaunch) agree on where logs go: ``$ROS_LOG_DIR``,
else ``$ROS_HOME/log``, else ``~/.ros/log`` (a leading ``~`` is expanded in both
variables). What they put there differs:

- ROS 2 nodes write ``<exe>_<pid>_<ms>.log`` files straight into it, ``ros2 launch``
  a directory per launch (``2026-11-22-10-08-41-123456-robot-4242/``);
- ROS 1 a directory per roscore run (named by its run id, a UUID), with a ``latest``
  symlink to the newest;
- ``console-tui rosout`` a directory per start (``rosout-2026-11-22-10-08-41-4242/``).

What ``purge`` may remove is decided by shape: a ROS 1 run (a UUID-named directory), a
``ros2 launch`` directory, a console-tui rosout directory, a ROS 2 node log file, and the
``latest`` link (``is_ros_entry``). Anything else at the top means the directory is not
(only) a log directory (``foreign_entries``); ``/``, the home directory and the directories
above it are never taken as one (``refused_log_dir``).

Each entry of the log directory is one *run*: a directory with everything under it, or a
single file. Symlinks are never followed: a symlink in the directory is an entry of its
own, of size 0, that is removed as a link (what it points to is never touched). Sizes are
the files' lengths (what ``du --apparent-size`` counts). A run's time is the newest
modification time of anything in it, so a directory still being written is never old.
"""

from __future__ import annotations

import os
import re
import shutil
import stat
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

_UUID = re.compile(r"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}\Z")
_LAUNCH = re.compile(r"\d{4}-\d\d-\d\d-\d\d-\d\d-\d\d-\d+-.+-\d+\Z")
_NODE_LOG = re.compile(r".+_\d+_\d+\.log\Z")


def ros_log_dir(environ: Mapping[str, str] | None = None) -> Path:
    """Where ROS writes its logs: ``$ROS_LOG_DIR``, else ``$ROS_HOME/log``, else ``~/.ros/log``."""
    env = os.environ if environ is None else environ
    home = env.get("HOME") or os.path.expanduser("~")

    def expand(text: str) -> Path:
        if text == "~" or text.startswith("~/"):
            text = home + text[1:]
        return Path(text)

    if env.get("ROS_LOG_DIR"):
        return expand(env["ROS_LOG_DIR"])
    if env.get("ROS_HOME"):
        return expand(env["ROS_HOME"]) / "log"
    return Path(home) / ".ros" / "log"


@dataclass(frozen=True)
class LogRun:
    """One entry of the log directory."""

    name: str
    #: ``directory``, ``file`` or ``symlink``.
    type: str
    size: int
    #: Newest modification time in it (seconds since the epoch).
    mtime: float
    files: int

    @property
    def kind(self) -> str:
        """What wrote it, as far as its name tells: for ``clean check``."""
        if self.type == "symlink":
            return "symlink"
        if self.type == "file":
            return "ROS 2 node log" if _NODE_LOG.match(self.name) else "file"
        if _UUID.match(self.name):
            return "ROS 1 run"
        if self.name.startswith("rosout-"):
            return "console-tui rosout"
        if _LAUNCH.match(self.name):
            return "ros2 launch"
        return "directory"


#: The kinds of entry that are ROS logs by their shape (``LogRun.kind``).
ROS_KINDS = frozenset({"ROS 1 run", "ros2 launch", "console-tui rosout", "ROS 2 node log"})
#: The link ROS 1 keeps to its newest run.
LATEST_LINK = "latest"


def is_ros_entry(run: LogRun) -> bool:
    """Whether ``run`` is a ROS log by its shape: the only entries ``purge`` removes."""
    if run.type == "symlink":
        return run.name == LATEST_LINK
    return run.kind in ROS_KINDS


def foreign_entries(runs: list[LogRun]) -> list[LogRun]:
    """The entries that are not ROS logs by their shape."""
    return [run for run in runs if not is_ros_entry(run)]


def refused_log_dir(log_dir: Path, home: str | None = None) -> str:
    """Why ``log_dir`` (resolved) can never be a log directory to clean, or "": it is ``/``,
    the home directory, or a directory above the home directory."""
    real = log_dir.resolve()
    home_dir = Path(home or os.path.expanduser("~")).resolve()
    if real == Path(real.anchor):
        return f"{real} is the root directory, not a log directory"
    if real == home_dir:
        return f"{real} is the home directory, not a log directory"
    if real in home_dir.parents:
        return f"{real} holds the home directory, not a log directory"
    return ""


def scan_runs(log_dir: Path) -> list[LogRun]:
    """The runs in ``log_dir``, oldest first; an empty list if it does not exist. A
    directory that is not a ROS log by its shape is not walked: its size and time are its own."""
    runs: list[LogRun] = []
    try:
        entries = list(os.scandir(log_dir))
    except (FileNotFoundError, NotADirectoryError):
        return []
    for entry in entries:
        try:
            info = entry.stat(follow_symlinks=False)
        except OSError:
            continue
        if stat.S_ISLNK(info.st_mode):
            runs.append(LogRun(entry.name, "symlink", 0, info.st_mtime, 0))
        elif stat.S_ISDIR(info.st_mode):
            run = LogRun(entry.name, "directory", 0, info.st_mtime, 0)
            if is_ros_entry(run):  # what is not a ROS log is never walked (a mis-set ROS_LOG_DIR=/opt)
                size, mtime, files = _tree(entry.path, info.st_mtime)
                run = LogRun(entry.name, "directory", size, mtime, files)
            runs.append(run)
        else:
            runs.append(LogRun(entry.name, "file", info.st_size, info.st_mtime, 1))
    runs.sort(key=lambda run: (run.mtime, run.name))
    return runs


def _tree(path: str, mtime: float) -> tuple[int, float, int]:
    """Total size, newest mtime and file count under a directory, never following symlinks."""
    size = files = 0
    stack = [path]
    while stack:
        try:
            entries = list(os.scandir(stack.pop()))
        except OSError:
            continue
        for entry in entries:
            try:
                info = entry.stat(follow_symlinks=False)
            except OSError:
                continue
            mtime = max(mtime, info.st_mtime)
            if stat.S_ISDIR(info.st_mode):
                stack.append(entry.path)
            elif not stat.S_ISLNK(info.st_mode):
                size += info.st_size
                files += 1
    return size, mtime, files


class UnsafeRemoval(Exception):
    """A removal that could reach outside the log directory was refused."""


def remove_run(log_dir: Path, run: LogRun) -> None:
    """Remove one run from ``log_dir``: a directory with all in it, a file, or a symlink
    itself. Never follows a symlink, so nothing outside ``log_dir`` is touched.
    Raises ``UnsafeRemoval`` if the entry is not a plain name in the directory or changed
    type since it was scanned, ``OSError`` if removing fails."""
    if not run.name or run.name in (".", "..") or "/" in run.name or "\0" in run.name:
        raise UnsafeRemoval(f"not an entry of the log directory: {run.name!r}")
    path = Path(log_dir) / run.name
    info = os.lstat(path)
    if stat.S_ISLNK(info.st_mode) or not stat.S_ISDIR(info.st_mode):
        if run.type == "directory":
            raise UnsafeRemoval(f"{run.name} is no longer a directory: left alone")
        os.unlink(path)
        return
    if run.type != "directory":
        raise UnsafeRemoval(f"{run.name} is now a directory: left alone")
    if not shutil.rmtree.avoids_symlink_attacks:  # pragma: no cover - Linux and macOS have it
        raise UnsafeRemoval("this platform cannot remove directories without a risk of following symlinks")
    shutil.rmtree(path)


def dangling_links(log_dir: Path) -> list[LogRun]:
    """Symlinks in ``log_dir`` that point at nothing (for example ``latest`` after a purge)."""
    return [run for run in scan_runs(log_dir) if run.type == "symlink" and not os.path.exists(Path(log_dir) / run.name)]
