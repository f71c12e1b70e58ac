"""Our threads under their own names in the operating system, so that ``top -H``, ``ps -L``
and ``/proc/PID/task/*/comm`` tell them apart (Python before 3.14 leaves every thread with the
process's name).

``os_named(target)`` is a thread's target that first gives the running thread, on Linux, the
name of its Python ``Thread`` without the ``console-tui-`` prefix, as ``ct-NAME`` cut to the
kernel's 15 bytes (``console-tui-intake-pipe`` is ``ct-intake-pipe``), then runs ``target``.
Elsewhere, or when the call fails, the name stays as it was.
"""

from __future__ import annotations

import ctypes
import sys
import threading
from collections.abc import Callable
from functools import wraps
from typing import Any

_PR_SET_NAME = 15
_PREFIX = "console-tui-"
#: The kernel keeps 15 bytes of a thread's name.
NAME_BYTES = 15


def os_name(python_name: str) -> bytes:
    """What the operating system calls a thread with this Python name."""
    short = python_name.removeprefix(_PREFIX) if python_name.startswith(_PREFIX) else python_name
    return ("ct-" + short).encode("ascii", "replace")[:NAME_BYTES]


def name_this_thread() -> None:
    """Give the running thread its ``os_name`` (Linux only; nothing happens elsewhere)."""
    if not sys.platform.startswith("linux"):
        return
    try:  # the process's own symbols hold libc's prctl: no library to look for
        ctypes.CDLL(None).prctl(_PR_SET_NAME, ctypes.c_char_p(os_name(threading.current_thread().name)), 0, 0, 0)
    except (OSError, AttributeError):
        pass


def os_named(target: Callable[..., Any]) -> Callable[..., Any]:
    """``target``, naming its thread first (``name_this_thread``)."""

    @wraps(target)
    def named(*args: Any, **kwargs: Any) -> Any:
        name_this_thread()
        return target(*args, **kwargs)

    return named
