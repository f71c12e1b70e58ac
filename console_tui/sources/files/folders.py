"""Folders of logs: which files a folder holds, the names that tell logs apart, the log
directory, and its newest run.

A folder opens as every log in it: a ROS 1 run folder (``~/.ros/log/<run_id>/``), a ROS 2
launch folder (``~/.ros/log/<date>-<host>-<pid>/``) or the whole log directory, searched
to any depth. Logs are known by their names: ``*.log`` and rotated ``*.log.<N>``, the
formats console-tui saves (``.csv``, ``.jsonl``), recordings (``.bag``, ``.mcap``,
``.db3``) and rosbag2 directories, each of which is one recording, and journal directories
(``*.journal`` files), each one journal. A log and its rotated
files (``rosout.log.2``, ``rosout.log.1``, ``rosout.log``) are one log, read oldest first,
so a record cut by a rotation comes back whole. Symbolic links to folders (``latest``) are
not followed there (the run they point to is in the folder anyway); empty files hold
nothing and are passed over.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ...model.formats import FormatError
from ...ros.log_dir import ros_log_dir
from ..journal.journal_location import is_journal_folder

#: File names read in a folder.
_LOG_NAME = re.compile(r".+\.(?:log(?:\.\d+)?|csv|jsonl|ndjson|bag|bag\.active|mcap|db3)\Z")
_ROTATED = re.compile(r"(?P<base>.+\.log)\.(?P<number>\d+)\Z")
#: A ROS 2 launch folder's name: its local start time, the host and launch's pid.
_LAUNCH_FOLDER = re.compile(r"(?P<time>\d{4}-\d\d-\d\d-\d\d-\d\d-\d\d)-\d{6}-.+-\d+\Z")
#: A ROS 2 node's log file: ``<executable>_<pid>_<milliseconds since the epoch>.log``.
_NODE_LOG = re.compile(r".+_\d+_(?P<ms>\d{13})\.log\Z")
#: A node started this long before its launch folder was made, or ended after its
#: launch.log last changed, still belongs to that run.
_RUN_MARGIN_MS = 5_000


@dataclass(frozen=True)
class LogPaths:
    """One log to open: a file, a rosbag2 directory, or a file and its rotated files.

    ``parts`` are read in order (oldest first); ``name`` is what its records carry as their
    source.
    """

    parts: tuple[Path, ...]
    name: str

    @property
    def path(self) -> Path:
        """The log's own path (the newest of its parts)."""
        return self.parts[-1]


@dataclass
class Expansion:
    """What a list of paths opens: the logs, and the files of folders that were passed over."""

    logs: list[LogPaths] = field(default_factory=list)
    #: Files in the folders that are not logs by their names, or empty.
    skipped: list[Path] = field(default_factory=list)
    #: Folders that could not be listed, with the reason.
    unreadable: list[tuple[Path, str]] = field(default_factory=list)
    #: Folders opened that hold no log at all.
    empty: list[Path] = field(default_factory=list)


def source_names(paths: Sequence[str | os.PathLike[str]]) -> list[str]:
    """Short names that tell the files apart: the file name, with as many parent
    directories as it takes when names repeat (``run1/rosout.log``, ``run2/rosout.log``)."""
    resolved = [Path(p).resolve() for p in paths]
    names = [p.name for p in resolved]
    depth = 1
    while len(set(names)) < len(names) and depth < 32:
        depth += 1
        counts = {n: names.count(n) for n in names}
        names = [
            "/".join(p.parts[-depth:]) if counts[name] > 1 else name for p, name in zip(resolved, names, strict=False)
        ]
    return names


def expand_paths(paths: Sequence[str | os.PathLike[str]]) -> Expansion:
    """Every log the paths name: files as they are, folders as the logs in them.

    Source names tell the logs apart: a file's name (with parent folders when names
    repeat); a folder's logs by their path inside it, under the folder's name when
    several things were opened.
    """
    expansion = Expansion()
    items: list[tuple[Path, list[tuple[tuple[Path, ...], str]] | None]] = []
    for given in paths:
        path = Path(given)
        if path.name == "metadata.yaml" and path.is_file():
            path = path.parent
        if path.is_dir() and not is_recording_folder(path) and not is_journal_folder(path):
            inside = _logs_in(path, expansion)
            if not inside:
                expansion.empty.append(path)
            items.append((path, inside))
        else:
            items.append((path, None))
    plain_names = iter(source_names([path for path, found in items if found is None]))
    several = len(items) > 1
    for path, found in items:
        if found is None:
            expansion.logs.append(LogPaths((path,), next(plain_names)))
            continue
        prefix = f"{path.resolve().name}/" if several else ""
        expansion.logs += [LogPaths(parts, prefix + name) for parts, name in found]
    seen: dict[str, int] = {}
    for index, log in enumerate(expansion.logs):
        if log.name in seen:  # the same name twice (two folders of one name): the full path tells them apart
            expansion.logs[index] = LogPaths(log.parts, str(log.path))
        seen[log.name] = index
    return expansion


def is_recording_folder(path: Path) -> bool:
    """Whether a folder is a rosbag2 recording (one recording, not a folder of logs); a
    folder that cannot be entered is not (walking it then reports it unreadable)."""
    try:
        return (path / "metadata.yaml").is_file()
    except OSError:
        return False


def _logs_in(folder: Path, expansion: Expansion) -> list[tuple[tuple[Path, ...], str]]:
    """The logs in a folder, as ``(parts, name inside the folder)``, in name order."""
    found: list[Path] = []
    skipped = expansion.skipped

    def unreadable(error: OSError) -> None:
        expansion.unreadable.append((Path(error.filename or folder), error.strerror or str(error)))

    for directory, subfolders, files in os.walk(folder, onerror=unreadable):
        here = Path(directory)
        kept = []
        for name in sorted(subfolders):
            sub = here / name
            if sub.is_symlink():
                continue
            if is_recording_folder(sub) or is_journal_folder(sub):  # one log
                found.append(sub)
            else:
                kept.append(name)
        subfolders[:] = kept
        for name in sorted(files):
            path = here / name
            if not _LOG_NAME.match(name):
                skipped.append(path)
                continue
            try:
                if path.stat().st_size == 0:
                    skipped.append(path)
                    continue
            except OSError:
                pass  # opening it will say what is wrong
            found.append(path)
    return [(parts, parts[-1].relative_to(folder).as_posix()) for parts in _rotations(found)]


def _rotations(paths: list[Path]) -> list[tuple[Path, ...]]:
    """Paths with each log's rotated files gathered before it, oldest first."""
    rotated: dict[Path, list[tuple[int, Path]]] = {}
    others: list[Path] = []
    for path in paths:
        match = _ROTATED.match(path.name)
        if match is not None:
            rotated.setdefault(path.with_name(match["base"]), []).append((int(match["number"]), path))
        else:
            others.append(path)
    logs: list[tuple[Path, ...]] = []
    for path in others:
        older = [p for _n, p in sorted(rotated.pop(path, []), reverse=True)]
        logs.append((*older, path))
    for older_parts in rotated.values():  # rotated files whose newest file is gone
        logs.append(tuple(p for _n, p in sorted(older_parts, reverse=True)))
    return sorted(logs, key=lambda parts: (str(parts[-1].parent), _ROTATED.sub(r"\g<base>", parts[-1].name)))


def latest_run(environ: Mapping[str, str] | None = None) -> list[Path]:
    """The newest run in the log directory, as paths to open.

    The folder ``latest`` points to (ROS 1 and ROS 2 launch both keep it), else the newest
    folder. For a ROS 2 launch folder, the nodes' own log files (kept beside the folders,
    not in them) whose names say they started during the run come too. Raises
    ``FormatError`` saying where it looked when there is no run.
    """
    directory = ros_log_dir(environ)
    if not directory.is_dir():
        raise FormatError(f"no ROS log directory at {directory} (set by ROS_LOG_DIR, else ROS_HOME/log)")
    latest = directory / "latest"
    if latest.is_dir():
        run = latest.resolve()
    else:
        runs = [p for p in directory.iterdir() if p.is_dir() and not p.is_symlink() and not is_recording_folder(p)]
        if not runs:
            raise FormatError(f"no run folders in the ROS log directory {directory}")
        run = max(runs, key=lambda p: p.stat().st_mtime_ns)
    return [run, *_node_logs_of_launch(run, directory)]


def _node_logs_of_launch(run: Path, directory: Path) -> list[Path]:
    """The ROS 2 node log files in ``directory`` written during the launch run ``run``."""
    match = _LAUNCH_FOLDER.match(run.name)
    launch_log = run / "launch.log"
    if match is None or not launch_log.is_file():
        return []
    import time

    try:
        start_ms = int(time.mktime(time.strptime(match["time"], "%Y-%m-%d-%H-%M-%S"))) * 1000
        end_ms = launch_log.stat().st_mtime_ns // 1_000_000
    except (ValueError, OverflowError, OSError):
        return []
    found = []
    for path in sorted(directory.iterdir()):
        node = _NODE_LOG.match(path.name)
        if (
            node is not None
            and path.is_file()
            and start_ms - _RUN_MARGIN_MS <= int(node["ms"]) <= end_ms + _RUN_MARGIN_MS
        ):
            found.append(path)
    return found
