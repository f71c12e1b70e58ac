"""Formatting and parsing of ROS time stamps (nanoseconds since the Unix epoch)."""

from __future__ import annotations

import time
from datetime import datetime, timezone
from functools import lru_cache

NS_PER_S = 1_000_000_000


def split_stamp(stamp_ns: int) -> tuple[int, int]:
    """``(sec, nanosec)`` of a stamp, nanosec always in 0..999,999,999."""
    return divmod(stamp_ns, NS_PER_S)


def stamp_text(stamp_ns: int) -> str:
    """``sec.nanosec`` with nanosec padded to 9 digits, as rqt_console writes stamps."""
    sec, nsec = split_stamp(stamp_ns)
    return f"{sec}.{nsec:09d}"


@lru_cache(maxsize=4096)
def _clock_of_second(sec: int, utc: bool) -> str | None:
    """``HH:MM:SS`` of a whole second (cached: a screen of rows shares a few seconds)."""
    try:
        parts = time.gmtime(sec) if utc else time.localtime(sec)
    except (OverflowError, OSError, ValueError):
        return None
    return f"{parts.tm_hour:02d}:{parts.tm_min:02d}:{parts.tm_sec:02d}"


def clock_text(stamp_ns: int, *, utc: bool = False, digits: int = 3) -> str:
    """``HH:MM:SS.mmm`` in local time (or UTC), for the table's time column."""
    sec, nsec = split_stamp(stamp_ns)
    clock = _clock_of_second(sec, utc)
    if clock is None:
        return stamp_text(stamp_ns)
    return f"{clock}.{nsec:09d}"[: len(clock) + 1 + digits] if digits else clock


def full_text(stamp_ns: int, *, utc: bool = False) -> str:
    """Date, time to the nanosecond and zone: ``2026-11-22 10:08:41.123456789 +0000``."""
    sec, nsec = split_stamp(stamp_ns)
    try:
        moment = datetime.fromtimestamp(sec, tz=timezone.utc)
        if not utc:
            moment = moment.astimezone()
    except (OverflowError, OSError, ValueError):
        return stamp_text(stamp_ns)
    return f"{moment:%Y-%m-%d %H:%M:%S}.{nsec:09d} {moment:%z}"


def duration_text(ns: int) -> str:
    """A duration in its unit, three digits at most: ``250 ms``, ``2.8 s``, ``5 min``, ``3 h``, ``2 days``."""
    seconds = ns / NS_PER_S
    if seconds < 1:
        return f"{seconds * 1000:.3g} ms"
    if seconds < 60:
        return f"{seconds:.3g} s"
    if seconds < 3600:
        return f"{seconds / 60:.3g} min"
    if seconds < 86_400:
        return f"{seconds / 3600:.3g} h"
    return f"{seconds / 86_400:.3g} days"
