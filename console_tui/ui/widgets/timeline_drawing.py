"""How the timeline strip is drawn: its four lines from ``Timeline.columns``, each bar's
severities stacked in eighths of a cell, the marks and the table's place on the axis.

A part of ``TimelineStrip`` (it mixes this in); why the strip draws its own bars rather than
using ``Sparkline`` or plotext: ``timeline_strip.py``.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from functools import lru_cache

from rich.segment import Segment
from rich.style import Style
from textual.strip import Strip
from textual.widget import Widget

from ...model.overview.timeline import Timeline, TimelineColumns
from ...model.timefmt import clock_text, duration_text

#: Eighths of a cell, bottom up.
_LOWER = " ▁▂▃▄▅▆▇█"
_BAR_ROWS = 2
_EIGHTHS = 8 * _BAR_ROWS
SEVERITIES = ("debug", "info", "warn", "error", "fatal")
_MARKS = ((4, "F"), (3, "E"), (2, "W"))
_NS_PER_S = 1_000_000_000
LINES = 4


@lru_cache(maxsize=4096)  # most columns keep their counts from one frame to the next
def stack(counts: tuple[int, ...], peak: int, eighths: int = _EIGHTHS) -> tuple[int, ...]:
    """Eighths of the bar for each severity: the bar as high as the total against ``peak``
    (at least one eighth when there is anything), each severity its share of it, and at least
    one eighth for any WARN, ERROR or FATAL."""
    total = sum(counts)
    if not total or peak <= 0:
        return (0,) * len(counts)
    height = max((total * eighths * 2 + peak) // (2 * peak), 1)
    if total in counts:  # one severity only (the common case)
        return tuple(height if count else 0 for count in counts)
    parts = [count * height / total for count in counts]
    shares = [int(part) for part in parts]
    for slot in range(2, len(counts)):
        if counts[slot] and not shares[slot]:
            shares[slot] = 1
    short = height - sum(shares)
    order = sorted(range(len(counts)), key=lambda s: parts[s] - int(parts[s]), reverse=True)
    for slot in order:
        if short <= 0:
            break
        if counts[slot]:
            shares[slot] += 1
            short -= 1
    while short < 0:  # the minimum eighths made it too high: take from the biggest share
        biggest = max(range(len(counts)), key=lambda s: shares[s])
        if shares[biggest] <= 1:
            break
        shares[biggest] -= 1
        short += 1
    return tuple(shares)


@lru_cache(maxsize=4096)
def bar_cells(shares: tuple[int, ...]) -> tuple[tuple[str, int | None, int | None], ...]:
    """The bar's cells, bottom up: (glyph, severity slot drawn, slot behind it or None)."""
    fill: list[int] = []
    for slot, share in enumerate(shares):
        fill.extend([slot] * share)
    fill = fill[:_EIGHTHS]
    cells: list[tuple[str, int | None, int | None]] = []
    for row in range(_BAR_ROWS):
        part = fill[row * 8 : row * 8 + 8]
        if not part:
            cells.append((" ", None, None))
        elif len(part) < 8:
            cells.append((_LOWER[len(part)], max(part), None))
        elif part[0] == part[-1]:
            cells.append(("█", part[0], None))
        else:
            top = part[-1]
            below = [slot for slot in part if slot != top]
            cells.append((_LOWER[len(below)], max(below), top))
    return tuple(cells)


def span_text(start_ns: int, end_ns: int, *, utc: bool) -> tuple[str, str]:
    """The strip's first and last time, as precise as the span needs."""
    span = end_ns - start_ns
    digits = 3 if span < 60 * _NS_PER_S else 0
    if span >= 86_400 * _NS_PER_S:
        return _dated(start_ns, utc), _dated(end_ns, utc)
    return clock_text(start_ns, utc=utc, digits=digits), clock_text(end_ns, utc=utc, digits=digits)


def _dated(stamp_ns: int, utc: bool) -> str:
    seconds = stamp_ns // _NS_PER_S
    try:
        parts = time.gmtime(seconds) if utc else time.localtime(seconds)
    except (OverflowError, OSError, ValueError):
        return str(seconds)
    return time.strftime("%Y-%m-%d %H:%M", parts)


def _runs(cells: Sequence[tuple[str, Style]]) -> list[Segment]:
    """Cells as segments, neighbours of the same style joined."""
    segments: list[Segment] = []
    text: list[str] = []
    current: Style | None = None
    for glyph, style in cells:
        if style is not current and style != current:
            if text:
                segments.append(Segment("".join(text), current))
            text, current = [], style
        text.append(glyph)
    if text:
        segments.append(Segment("".join(text), current))
    return segments


def rate_text(rate: float) -> str:
    """A rate for people: ``12k/s``, ``250/s``, ``0.5/s``; slower ones a minute, an hour or a
    day (``3/min``, ``40/h``, ``0.2/day``: a file that spans years), never ``7.7e-07/s``."""
    if rate >= 10_000:
        return f"{rate / 1000:,.0f}k/s"
    if rate <= 0:
        return "0/s"
    for unit, seconds in (("s", 1), ("min", 60), ("h", 3600), ("day", 86_400)):
        per = rate * seconds
        if per >= 0.1 or unit == "day":
            return f"{per:,.0f}/{unit}" if per >= 10 else f"{per:.2g}/{unit}"
    raise AssertionError("unreachable")


class TimelineDrawing(Widget):
    """The strip's lines for a width (``TimelineStrip`` mixes this in)."""

    # What it reads of the strip (``TimelineStrip`` sets them).
    timeline: Timeline
    utc: bool
    position: tuple[int, int] | None
    filtered: bool
    _columns: TimelineColumns | None
    picked_column: Callable[[TimelineColumns], int | None]

    def _style(self, name: str) -> Style:
        return self.get_component_rich_style(f"timeline--{name}", partial=True)

    def _draw(self, width: int) -> list[Strip]:
        base = self.rich_style
        columns = self._columns = self.timeline.columns(width) if width > 0 else None
        if columns is None:
            note = "Timeline: no rows shown" if self.filtered else "Timeline: no messages yet"
            label = Strip([Segment(note, base + self._style("label"))]).adjust_cell_length(width, base)
            return [label, *(Strip.blank(width, base) for _ in range(LINES - 1))]
        return [
            self._label_line(columns, width, base),
            *self._bar_lines(columns, width, base),
            self._mark_line(columns, width, base),
        ]

    def _label_line(self, columns: TimelineColumns, width: int, base: Style) -> Strip:
        style = base + self._style("label")
        first, last = span_text(columns.start_ns, columns.newest_ns, utc=self.utc)
        picked = self.picked_column(columns)
        if picked is not None:
            counts = columns.counts[picked]
            start = columns.start_ns + picked * columns.step_ns
            when = clock_text(start, utc=self.utc, digits=3 if columns.step_ns < 60 * _NS_PER_S else 0)
            marks = " ".join(f"{letter}{counts[slot]:,}" for slot, letter in reversed(_MARKS) if counts[slot])
            middle = (
                f"▸ {when} +{duration_text(columns.step_ns)}: {sum(counts):,} row{'' if sum(counts) == 1 else 's'}"
                + (f" {marks}" if marks else "")
            )
        else:
            middle = f"{duration_text(columns.step_ns)} a column, peak {rate_text(columns.peak_rate())}"
            if self.filtered:
                middle += ", shown rows only"
            if self.timeline.recounting:
                middle += ", counting…"
        left = f"{first}  {middle}"
        room = width - len(last) - 1
        if room < len(first):
            text = left[:width]
        else:
            text = left[:room].ljust(room) + " " + last
        return Strip([Segment(text, style)]).adjust_cell_length(width, base)

    def _bar_lines(self, columns: TimelineColumns, width: int, base: Style) -> list[Strip]:
        severities = [base + self._style(name) for name in SEVERITIES]
        picked_style = self._style("picked")
        styles: dict[tuple[int | None, int | None, bool], Style] = {}

        def style_of(slot: int | None, behind: int | None, picked: bool) -> Style:
            style = styles.get((slot, behind, picked))
            if style is None:
                style = severities[slot] if slot is not None else base
                if behind is not None and severities[behind].color is not None:
                    style = style + Style(bgcolor=severities[behind].color)
                if picked:
                    style = style + picked_style
                styles[(slot, behind, picked)] = style
            return style

        peak = max(columns.totals(), default=0)
        picked = self.picked_column(columns)
        rows: list[list[tuple[str, Style]]] = [[] for _ in range(_BAR_ROWS)]
        for column, counts in enumerate(columns.counts):
            for row, (glyph, slot, behind) in enumerate(bar_cells(stack(counts, peak))):
                rows[_BAR_ROWS - 1 - row].append((glyph, style_of(slot, behind, column == picked)))
        return [Strip(_runs(cells)).adjust_cell_length(width, base) for cells in rows]

    def _mark_line(self, columns: TimelineColumns, width: int, base: Style) -> Strip:
        axis, position = base + self._style("axis"), base + self._style("position")
        marks = [base + self._style(name) + Style(bold=True) for name in SEVERITIES]
        inside_marks = [mark + Style(reverse=True) for mark in marks]
        picked_style = self._style("picked")
        picked = self.picked_column(columns)
        here = None
        if self.position is not None:
            here = (columns.column_of(self.position[0]), columns.column_of(self.position[1]))
        segments: list[tuple[str, Style]] = []
        for column, counts in enumerate(columns.counts):
            inside = here is not None and here[0] <= column <= here[1]
            glyph, style = ("━", position) if inside else ("─", axis)
            for slot, letter in _MARKS:
                if counts[slot]:
                    glyph, style = letter, (inside_marks if inside else marks)[slot]
                    break
            if column == picked:
                style = style + picked_style
            segments.append((glyph, style))
        return Strip(_runs(segments)).adjust_cell_length(width, base)
