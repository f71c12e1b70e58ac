"""The nodes' output files of a roslaunch run, followed as they appear and grow.

roslaunch sends the standard output of each node launched with ``output="log"`` (its
default) to ``<run folder>/<process>-stdout.log`` (``roslaunch/nodeprocess.py``), so what
such a node prints never reaches roslaunch's terminal. The run folder is the one roslaunch
names in its first line (``... logging to <folder>/roslaunch-<host>-<pid>.log``). Each
``*-stdout.log`` and ``*-stderr.log`` file there written since the launch started is read
as the files are read (``files/follow.py``: whole lines, across a truncation), its node
named from the file (``printer-2-stdout.log``: ``/printer``).
"""

from __future__ import annotations

import os
import re
import time
from pathlib import Path

from ...model.formats import FormatError
from ...model.store.record import LogRecord
from ..files.follow import FollowedFile
from ..files.log_file import TextLogFile
from ..files.opener import open_log_file

#: roslaunch's first line, naming its log file in the run folder.
_LOGGING_TO = re.compile(r"\.\.\. logging to (?P<path>/.+)/roslaunch-[^/]+\.log\Z")
_OUTPUT = re.compile(r".+-(?:stdout|stderr)\.log\Z")
#: How often the folder is looked at for new files.
LOOK_S = 0.25


def run_folder(line: str) -> Path | None:
    """The run folder roslaunch's ``... logging to`` line names, or None."""
    found = _LOGGING_TO.match(line)
    return Path(found["path"]) if found is not None else None


class NodeOutputs:
    """The output files in ``folder`` written since ``since_ns`` (wall clock), followed."""

    def __init__(self, folder: Path, since_ns: int) -> None:
        self.folder = folder
        self.since_ns = since_ns
        self.followed: dict[str, FollowedFile] = {}
        self._looked = 0.0

    def read(self, now: float | None = None) -> list[LogRecord]:
        """What the files hold that was not read yet (new files read from their start)."""
        now = time.monotonic() if now is None else now
        records: list[LogRecord] = []
        if now - self._looked >= LOOK_S:
            self._looked = now
            records += self._new_files()
        for followed in self.followed.values():
            records += followed.read(now=now)
        return records

    def _new_files(self) -> list[LogRecord]:
        records: list[LogRecord] = []
        try:
            names = sorted(os.listdir(self.folder))
        except OSError:
            return records
        for name in names:
            if name in self.followed or not _OUTPUT.match(name):
                continue
            path = self.folder / name
            try:
                info = path.stat()
                if info.st_size == 0 or info.st_mtime_ns < self.since_ns:
                    continue  # nothing yet, or a file of an earlier launch (the same master's run)
                opened = open_log_file(path)
            except (OSError, FormatError):
                continue
            if not isinstance(opened, TextLogFile):
                continue
            followed = self.followed[name] = FollowedFile(opened)
            for batch in followed.records_so_far():
                records += batch
        return records

    def close(self) -> None:
        for followed in self.followed.values():
            followed.close()
