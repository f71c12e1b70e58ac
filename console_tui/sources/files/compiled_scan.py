"""The ROS 2 log line scanner in C (``rcutils_scan.c``), compiled on this machine the first time it is needed.

Reading a ROS 2 node log file in Python costs 5-8 µs a record: a night's 20 million lines
would take minutes to index. The scanner reads the lines of rcutils' default format at
about 1 GB/s and stops at any line it cannot read exactly as the Python reader does, which
then reads that part (``file_index.py``). It needs only a C compiler and Python's headers, and
is built and cached as ``c_build`` does for the intake's loops in C. Without them (or with
``CONSOLE_TUI_COMPILED_SCAN=0``) the Python reader reads every line: the same index, slower.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any, NamedTuple

from ...system import c_build

SOURCE = Path(__file__).with_name("rcutils_scan.c")
MODULE = "console_tui_rcutils_scan"
STEM = "rcutils_scan"
#: ``0`` keeps the Python reader for every line (to compare the two, or if the scanner misbehaves).
SWITCH = "CONSOLE_TUI_COMPILED_SCAN"
BUILD_TIMEOUT_S = 60.0

#: ``scan(data, start, end, max_records, nodes, new_names, want_messages, at_eof)``: see rcutils_scan.c.
ScanFunction = Callable[..., tuple[Any, ...]]


class Scanner(NamedTuple):
    """What the built module offers: ``scan``, and ``contains(data, needle, ignore_case)``
    (memmem, or ASCII letters compared ignoring case with a lower-case needle)."""

    scan: ScanFunction
    contains: Callable[[bytes, bytes, bool], bool]


_loaded: tuple[Scanner | None, str] | None = None
_build_lock = threading.Lock()


def load() -> tuple[Scanner | None, str]:
    """The compiled scanner and ``""`` (or a note on how it was built), or ``None`` and why
    not (built once, then cached)."""
    global _loaded
    with _build_lock:
        if _loaded is None:
            _loaded = c_build.noted(_load)
        return _loaded


def _load() -> tuple[Scanner | None, str]:
    if os.environ.get(SWITCH, "1") == "0":
        return None, f"{SWITCH}=0"
    module, note = c_build.load_or_build(f"{STEM}_{build_key()}{c_build.suffix()}", STEM, MODULE, build)
    return (None if module is None else Scanner(module.scan, module.contains)), note


def build_key() -> str:
    """What the built file depends on: the C source and this Python."""
    return c_build.source_key(SOURCE)


def build(target: Path) -> str:
    """Compile ``rcutils_scan.c`` into ``target``; ``""``, or what went wrong."""
    return c_build.compile_module(SOURCE, target, BUILD_TIMEOUT_S)
