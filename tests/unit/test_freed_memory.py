"""Freed memory given back to the operating system (glibc's ``malloc_trim``): the resident
size falls after a large freed heap, and the call is harmless where it cannot be made."""

from __future__ import annotations

import ctypes
import os
import sys

import pytest

from console_tui.system import freed_memory
from console_tui.system.freed_memory import give_back


def resident_kb() -> int:
    with open(f"/proc/{os.getpid()}/status") as status:
        return next(int(line.split()[1]) for line in status if line.startswith("VmRSS:"))


@pytest.mark.skipif(not hasattr(ctypes.CDLL(None), "malloc_trim"), reason="no glibc malloc_trim here")
def test_the_heap_freed_is_given_back():
    # Many small blocks (malloc's heap, not mmap), the first of each pair kept so that the
    # heap's top does not shrink by itself, then the rest freed.
    kept, freed = [], []
    for _ in range(1_000):
        kept.append(bytearray(600))
        freed.append(bytearray(80_000))  # under malloc's mmap threshold: in its heap
    before = resident_kb()
    del freed
    assert give_back()
    assert resident_kb() < before - 40_000  # most of the 80 MB freed is given back
    assert len(kept) == 1_000


def test_elsewhere_nothing_happens(monkeypatch):
    monkeypatch.setattr(sys, "platform", "darwin")
    assert give_back() is False
    monkeypatch.setattr(sys, "platform", "linux")
    monkeypatch.setattr(freed_memory.ctypes, "CDLL", lambda _name: object())  # a C library without it
    assert give_back() is False
