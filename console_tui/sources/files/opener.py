"""Opening any log file or recording by path: what it is, and a reader for it."""

from __future__ import annotations

import os
import stat
from pathlib import Path

from ...model.formats import FormatError, Ros1ConsoleFormat, detect_text_format, recording_kind, text_formats
from ...model.formats.detect import HEAD_SIZE
from ...model.formats.ros1_console import is_capture_name
from ..journal.journal_location import JOURNAL_MAGIC, is_journal_folder
from .folders import LogPaths
from .log_file import LogFile, TextLogFile

#: The environment variable rcutils reads its output format from.
FORMAT_VARIABLE = "RCUTILS_CONSOLE_OUTPUT_FORMAT"


def open_log_file(path: str | os.PathLike[str], *, log_format: str | None = None, source: str | None = None) -> LogFile:
    """Open a log file or recording for reading, detecting its format from its content.

    Text files: rqt_console CSV, JSON Lines, ROS 1 rosout.log, ROS 2 log files (the
    default rcutils format, ``log_format`` when given, else also the template in
    ``$RCUTILS_CONSOLE_OUTPUT_FORMAT``). Recordings: ROS 1 ``.bag``, rosbag2 ``.mcap``,
    ``.db3`` or a rosbag2 directory (or its ``metadata.yaml``). The systemd journal: a
    journal file or a directory of them (``journal_file.py``).

    ``source`` (default: the file's name) is what every record will carry. Raises
    ``FormatError`` with a message for the user when the file cannot be read at all.
    """
    file_path = Path(path)
    if file_path.name == "metadata.yaml" and file_path.is_file():
        file_path = file_path.parent
    name = source or file_path.name or str(file_path)
    try:
        mode = file_path.stat().st_mode
    except FileNotFoundError:
        raise FormatError(f"{name}: no such file or directory") from None
    except OSError as error:
        raise FormatError(f"{name}: cannot read: {error.strerror or error}") from None
    if not stat.S_ISDIR(mode) and not stat.S_ISREG(mode):
        raise FormatError(f"{name}: {_not_regular(mode)}, not a file: only files and folders are read")
    if stat.S_ISDIR(mode) and is_journal_folder(file_path):
        return _journal(file_path, name, log_format)
    if stat.S_ISDIR(mode):
        from .recordings import open_recording

        return open_recording(file_path, name, "rosbag2")
    try:
        with open(file_path, "rb") as stream:
            head = stream.read(HEAD_SIZE)
    except OSError as error:
        raise FormatError(f"{name}: cannot read: {error.strerror or error}") from None
    if head.startswith(JOURNAL_MAGIC):
        return _journal(file_path, name, log_format)
    kind = recording_kind(head)
    if kind is not None:
        from .recordings import open_recording

        return open_recording(file_path, name, kind)
    if file_path.suffix in (".bag", ".mcap", ".db3") and head:
        raise FormatError(f"{file_path.name}: named like a recording, but it does not start like one (damaged?)")
    env_template = os.environ.get(FORMAT_VARIABLE, "")
    candidates = text_formats(log_format, (env_template,) if env_template else ())
    fallback = Ros1ConsoleFormat() if is_capture_name(file_path.name) else None
    return TextLogFile(file_path, name, detect_text_format(head, candidates, file_path.name, fallback=fallback))


def open_log_paths(log: LogPaths, *, log_format: str | None = None) -> LogFile:
    """Open one log of a folder: a file, a recording, or a log and its rotated files
    (read as one, in the format of the first part whose start says it)."""
    if len(log.parts) == 1:
        return open_log_file(log.path, log_format=log_format, source=log.name)
    env_template = os.environ.get(FORMAT_VARIABLE, "")
    candidates = text_formats(log_format, (env_template,) if env_template else ())
    fallback = Ros1ConsoleFormat() if is_capture_name(log.path.name) else None
    error: FormatError | None = None
    for part in log.parts:
        try:
            with open(part, "rb") as stream:
                head = stream.read(HEAD_SIZE)
            return TextLogFile(
                log.path, log.name, detect_text_format(head, candidates, part.name, fallback=fallback), log.parts
            )
        except FormatError as failure:
            error = error or failure
        except OSError as failure:
            error = error or FormatError(f"{part.name}: cannot read: {failure.strerror or failure}")
    assert error is not None
    raise FormatError(f"{log.name}: {error!s}") from None


def _journal(path: Path, name: str, log_format: str | None) -> LogFile:
    from .journal_file import JournalFile

    return JournalFile.of_path(path, name, template=log_format or os.environ.get(FORMAT_VARIABLE, ""))


def _not_regular(mode: int) -> str:
    """What a file that is neither a regular file nor a directory is."""
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO)"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "a special file"
