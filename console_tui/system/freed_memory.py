"""Memory the process freed given back to the operating system: ``give_back()``.

A page of the log warehouse (50,000 rows) is a few tens of MB while it is read and placed,
then freed; glibc's ``malloc`` keeps much of that in its heap, so the console's resident size
stays as high as the largest page made it (about 10 MB over a store of the same records made
in memory). ``malloc_trim(0)`` hands the heap's free pages back (a few ms on a heap of 150 MB;
Dask's workers do the same). Where the C library has no ``malloc_trim`` (musl, macOS) or the
call fails, nothing happens.
"""

from __future__ import annotations

import ctypes
import sys


def give_back() -> bool:
    """Give the heap's free memory back to the operating system; whether it was asked."""
    if not sys.platform.startswith("linux"):
        return False
    try:  # the process's own symbols hold the C library's: no library to look for
        ctypes.CDLL(None).malloc_trim(0)
    except (OSError, AttributeError):
        return False
    return True
