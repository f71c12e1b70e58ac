"""Log files and recordings as record sources: open, read in batches, merge, load in
the background. Text formats live in ``console_tui.model.formats``; recordings need
the ``files`` extra (rosbags, mcap).

The UI's entry points:

- ``FileLoad(paths, queue, log_format=..., on_change=...)``: ``start()``, ``cancel()``,
  ``progress`` (``LoadProgress``), ``problems()``;
- ``open_log_file(path)`` -> ``LogFile`` (``batches(cancel)``, ``done``/``total``,
  ``problems``), and ``load_records(files, cancel)`` to merge in the caller's thread;
- saving: ``console_tui.model.formats.save_records(records, path, format)``.
"""

from __future__ import annotations

from ...model.formats import FormatError, Problem
from .loader import FileLoad, FileProgress, LoadProgress, load_records, open_files
from .log_file import LogFile, TextLogFile
from .merge import merge_by_time, sorted_by_stamp
from .opener import open_log_file, source_names

__all__ = [
    "FileLoad",
    "FileProgress",
    "FormatError",
    "LoadProgress",
    "LogFile",
    "Problem",
    "TextLogFile",
    "load_records",
    "merge_by_time",
    "open_files",
    "open_log_file",
    "sorted_by_stamp",
    "source_names",
]
