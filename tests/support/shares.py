"""What of a range of ROS domain ids or ports this xdist worker may use: each worker takes
turns through a share of its own, so parallel tests never meet on one."""

from __future__ import annotations

import itertools
import os
from collections.abc import Callable, Iterator

import pytest


def worker() -> tuple[int, int]:
    """This xdist worker's number and how many workers there are."""
    name = os.environ.get("PYTEST_XDIST_WORKER", "gw0")
    digits = "".join(ch for ch in name if ch.isdigit())
    count = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1") or 1)
    return int(digits or 0) % max(count, 1), max(count, 1)


def range_of(variable: str, default: tuple[int, int], lowest: int, highest: int, example: str) -> tuple[int, int]:
    """``variable``'s FIRST-LAST (both included, within ``lowest``-``highest``), else ``default``."""
    text = os.environ.get(variable, "").strip()
    if not text:
        return default
    try:
        first, _, last = text.partition("-")
        low, high = int(first), int(last or first)
    except ValueError:
        raise pytest.UsageError(f"{variable}={text!r}: write it as FIRST-LAST, for example {example}") from None
    if not lowest <= low <= high <= highest:
        raise pytest.UsageError(f"{variable}={text!r}: they run from {lowest} to {highest}, first <= last")
    return low, high


def taker(bounds: Callable[[], tuple[int, int]]) -> Callable[[], Iterator[int]]:
    """A function giving, each time, this worker's share of ``bounds()`` in turns from where
    the last call stopped (the caller takes the first that suits it)."""
    counter = itertools.count()

    def share() -> Iterator[int]:
        low, high = bounds()
        number, workers = worker()
        size = max((high - low + 1) // workers, 1)
        for _ in range(size):
            yield low + (number * size + next(counter) % size) % (high - low + 1)

    return share
