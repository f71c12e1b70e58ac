"""Log files and recordings as record sources: open, read in batches, merge, load in
the background. Text formats live in ``console_tui.model.formats``; recordings need
the ``files`` extra (rosbags, mcap).

The UI's entry points:

- ``FileLoad(paths, sink, log_format=..., on_change=...)`` (``sink``: an ``IntakeQueue``, or
  a callable taking each batch, ``RecordColumns``): ``start()``, ``cancel()``, ``progress`` (``LoadProgress``),
  ``problems()``, ``notes()``; a path may be a folder (every log in it, ``folders``);
- ``open_logs(paths)`` -> ``OpenedLogs`` (files, failures, skipped), ``open_log_file(path)``
  -> ``LogFile`` (``batches(cancel)``, ``done``/``total``, ``problems``, ``notes()``), and
  ``load_records(files, cancel)`` to merge in the caller's thread;
- ``latest_run()``: the paths of the newest run in the ROS log directory;
- saving: ``console_tui.model.formats.save_records(records, path, save_format)``.
"""

from __future__ import annotations

from ...model.formats import FormatError, Problem
from .folders import latest_run, source_names
from .loader import FileLoad, FileProgress, LoadProgress, OpenedLogs, load_records, open_files, open_logs
from .log_file import LogFile, TextLogFile
from .merge import merge_by_time, sorted_by_stamp
from .opener import open_log_file

__all__ = [
    "FileLoad",
    "FileProgress",
    "FormatError",
    "LoadProgress",
    "LogFile",
    "OpenedLogs",
    "Problem",
    "TextLogFile",
    "latest_run",
    "load_records",
    "merge_by_time",
    "open_files",
    "open_log_file",
    "open_logs",
    "sorted_by_stamp",
    "source_names",
]
