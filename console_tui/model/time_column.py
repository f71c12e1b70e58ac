"""What the table's Time column shows: the formats a person switches between, and sim time.

- ``CLOCK``: the wall clock, ``HH:MM:SS.mmm`` (local time, or UTC);
- ``DATE``: date and time, ``YYYY-MM-DD HH:MM:SS.mmm``;
- ``STAMP``: the ROS stamp as it was sent, ``sec.nanosec``;
- ``SINCE_FIRST``: time since the first message kept, ``+1:02.250``;
- ``SINCE_ROW``: time since the selected row (negative above it);
- ``DELTA``: time since the row above.

Durations read ``+S.mmm``, ``+M:SS.mmm``, ``+H:MM:SS.mmm``, ``+Nd HH:MM:SS``: a sign, then
the fewest fields that hold it. ``sim_time_note`` says when stamps look like simulated time
(a clock that started near 0, or one far from this computer's), so that a wall clock of
``00:03:12`` on 1 January 1970 is not taken for a date.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum

from .timefmt import NS_PER_S, clock_text, split_stamp, stamp_text

#: Stamps before this (2001-09-09) are taken for simulated time: a sim clock starts at 0.
SIM_TIME_BEFORE_S = 1_000_000_000
#: A stamp further than this from the wall clock looks like another clock's (live sources).
FAR_FROM_WALL_CLOCK_S = 24 * 3600


class TimeFormat(str, Enum):
    CLOCK = "clock"
    DATE = "date"
    STAMP = "stamp"
    SINCE_FIRST = "since_first"
    SINCE_ROW = "since_row"
    DELTA = "delta"

    @property
    def relative(self) -> bool:
        return self in (TimeFormat.SINCE_FIRST, TimeFormat.SINCE_ROW, TimeFormat.DELTA)


@dataclass(frozen=True)
class FormatInfo:
    #: The column's title.
    title: str
    #: Its width in cells.
    width: int
    #: How the palette and the status line name it.
    name: str


_INFO = {
    TimeFormat.CLOCK: FormatInfo("Time", 12, "wall clock"),
    TimeFormat.DATE: FormatInfo("Date and time", 23, "date and time"),
    TimeFormat.STAMP: FormatInfo("Stamp", 20, "ROS stamp as sent"),
    TimeFormat.SINCE_FIRST: FormatInfo("Since first", 13, "time since the first message"),
    TimeFormat.SINCE_ROW: FormatInfo("Since row", 13, "time since the selected row"),
    TimeFormat.DELTA: FormatInfo("Δ previous", 13, "time since the row above"),
}
#: The order ``t`` steps through.
FORMATS: tuple[TimeFormat, ...] = tuple(TimeFormat)


def format_info(fmt: TimeFormat) -> FormatInfo:
    return _INFO[fmt]


def column_title(fmt: TimeFormat, utc: bool) -> str:
    """The Time column's title: ``Time``, ``Time UTC``, ``Since first``..."""
    title = _INFO[fmt].title
    return f"{title} UTC" if utc and fmt in (TimeFormat.CLOCK, TimeFormat.DATE) else title


def next_format(fmt: TimeFormat) -> TimeFormat:
    return FORMATS[(FORMATS.index(fmt) + 1) % len(FORMATS)]


def offset_text(ns: int) -> str:
    """A signed duration, milliseconds truncated: ``+0.137``, ``-1:02.500``, ``+2d 03:04:05``."""
    if ns == 0:
        return "0.000"
    sign = "+" if ns > 0 else "-"
    seconds, rest = divmod(abs(ns), NS_PER_S)
    millis = rest // 1_000_000
    minutes, secs = divmod(seconds, 60)
    hours, mins = divmod(minutes, 60)
    days, hrs = divmod(hours, 24)
    if days:
        return f"{sign}{days}d {hrs:02d}:{mins:02d}:{secs:02d}"
    if hours:
        return f"{sign}{hours}:{mins:02d}:{secs:02d}.{millis:03d}"
    if minutes:
        return f"{sign}{minutes}:{secs:02d}.{millis:03d}"
    return f"{sign}{secs}.{millis:03d}"


def date_text(stamp_ns: int, *, utc: bool = False) -> str:
    """``YYYY-MM-DD HH:MM:SS.mmm`` (local time, or UTC); the stamp as sent if out of range."""
    import time

    sec, _nsec = split_stamp(stamp_ns)
    try:
        parts = time.gmtime(sec) if utc else time.localtime(sec)
    except (OverflowError, OSError, ValueError):
        return stamp_text(stamp_ns)
    return f"{parts.tm_year:04d}-{parts.tm_mon:02d}-{parts.tm_mday:02d} {clock_text(stamp_ns, utc=utc)}"


def time_cell(
    stamp_ns: int,
    fmt: TimeFormat,
    *,
    utc: bool = False,
    origin_ns: int | None = None,
    previous_ns: int | None = None,
) -> str:
    """The Time cell of a row. ``origin_ns``: the first message's stamp (``SINCE_FIRST``) or
    the selected row's (``SINCE_ROW``); ``previous_ns``: the row above's (``DELTA``, blank
    for the first row)."""
    if fmt is TimeFormat.CLOCK:
        return clock_text(stamp_ns, utc=utc)
    if fmt is TimeFormat.DATE:
        return date_text(stamp_ns, utc=utc)
    if fmt is TimeFormat.STAMP:
        return stamp_text(stamp_ns)
    if fmt is TimeFormat.DELTA:
        return offset_text(stamp_ns - previous_ns) if previous_ns is not None else ""
    return offset_text(stamp_ns - origin_ns) if origin_ns is not None else ""


def sim_time_note(stamp_ns: int, now_ns: int, *, live: bool) -> str:
    """Why ``stamp_ns`` looks like simulated time, or ``""``: near 0, or (from a live source)
    far from ``now_ns``, this computer's clock; files may be old, so only a stamp in the
    future counts as far for them."""
    seconds = stamp_ns // NS_PER_S
    if 0 <= seconds < SIM_TIME_BEFORE_S:
        return "stamps look like sim time (near 0)"
    ahead = (stamp_ns - now_ns) // NS_PER_S
    if ahead > FAR_FROM_WALL_CLOCK_S or (live and -ahead > FAR_FROM_WALL_CLOCK_S):
        return "stamps look like sim time (far from this clock)"
    return ""
