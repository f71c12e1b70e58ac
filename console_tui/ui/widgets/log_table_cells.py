"""How the log table draws one row, and its header: a record's cells fitted to the columns'
widths and styled (severity, rules, cursor, selection, search matches, storm counts) into a
``Strip``.

A part of ``LogTable`` (it mixes this in); ``log_table_frame.py`` calls it for the rows a frame
shows that are not cached yet, with the styles and columns it worked out once for the frame.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from functools import lru_cache

from rich.cells import cell_len, set_cell_size
from rich.segment import Segment
from rich.style import Style
from textual.scroll_view import ScrollView
from textual.strip import Strip

from ...model.inert_text import one_line, shorten_name
from ...model.levels import severity_level, severity_name
from ...model.overview.storms import StormBadge
from ...model.store.log_store import LogStore
from ...model.store.record import LogRecord
from ...model.time_column import TimeFormat, column_title, time_cell
from ...model.timefmt import clock_text, duration_text
from .table_columns import PlacedColumn

#: How a row is marked by the rules: None (plain), "highlight" or "dim".
Decoration = str | None
#: Where a search matches in a message as shown: (start, end) character spans.
Spans = list[tuple[int, int]]

#: Cells of the gutter (a mark, and a space).
GUTTER = 2
_MESSAGE_LIMIT = 2000


class TableCells(ScrollView):
    """The header's and a row's strip (``LogTable`` mixes this in)."""

    # What it reads of the table (``LogTable`` sets them).
    store: LogStore
    utc: bool
    time_format: TimeFormat
    gutter_of: Callable[[int], str] | None
    match_spans: Callable[[int, str], Spans] | None
    #: A fleet's robots' colours (``--fleet``'s ``colour``) by name, for the Robot column.
    robot_styles: dict[str, Style]
    #: The component styles by class name (``log_table_frame.py`` looks them up).
    _styles: dict[str, Style]

    def _header(self, placed: tuple[PlacedColumn, ...], width: int, base: Style) -> Strip:
        style = base + self._styles.get("log-table--header", Style())
        segments: list[Segment] = []
        if self.gutter_of is not None:
            segments.append(Segment(" " * GUTTER, style))
        for place in placed:
            title = column_title(self.time_format, self.utc) if place.column.key == "time" else place.column.title
            segments.append(Segment(fit(title, place.width, place.column.align) + " ", style))
        return Strip(segments).adjust_cell_length(width, style)

    def _render_row(
        self,
        record: LogRecord,
        placed: tuple[PlacedColumn, ...],
        width: int,
        base: Style,
        is_cursor: bool,
        selected: bool,
        decoration: Decoration,
        badge: StormBadge | None = None,
        gutter: str | None = None,
        relative: int | None = None,
    ) -> Strip:
        styles = self._styles
        name = severity_level(record.level).style
        row_style = base + styles.get(f"log-table--row-{name}", Style())
        if decoration == "highlight":
            row_style += styles.get("log-table--highlight", Style())
        elif decoration == "dim":
            row_style += styles.get("log-table--dimmed", Style())
        if selected:
            row_style += styles.get("log-table--selected", Style())
        if is_cursor:
            row_style += styles.get("log-table--cursor", Style())
        muted = styles.get("log-table--dim-column", Style())
        row = _RowSegments()
        add = row.add
        if gutter is not None:
            add(fit(gutter, 1), row_style + styles.get("log-table--gutter", Style()))
            add(" ", row_style)
        for place in placed:
            key = place.column.key
            if key == "message" and badge is not None:
                mark = self._badge_text(badge, place.width)
                add(mark, row_style + styles.get("log-table--storm", Style()))
                room = place.width - len(mark)
                text = self._cell_text(record, key, room)
                for segment in self._message_segments(record.seq, text, fit(text, room), row_style):
                    add(*segment[:2])
                add(" ", row_style)
                continue
            if key == "time":
                text = time_cell(
                    record.stamp_ns, self.time_format, utc=self.utc, origin_ns=relative, previous_ns=relative
                )
            else:
                text = self._cell_text(record, key, place.width)
            style = row_style
            if key == "severity" and not is_cursor:
                style = row_style + styles.get(f"log-table--severity-{name}", Style())
            elif key == "robot" and not is_cursor and record.robot in self.robot_styles:
                style = row_style + self.robot_styles[record.robot]
            elif key in ("seq", "time", "file", "function", "line", "source") and name != "debug" and not is_cursor:
                style = row_style + muted
            fitted = fit(text, place.width, place.column.align)
            if key == "message":
                for segment in self._message_segments(record.seq, text, fitted, style):
                    add(*segment[:2])
            else:
                add(fitted, style)
            add(" ", row_style)
        return row.strip(width, row_style)

    def _message_segments(self, seq: int, text: str, fitted: str, style: Style) -> list[Segment]:
        """The message cell, with where a search matches marked."""
        spans = self.match_spans(seq, text) if self.match_spans else None
        if spans:
            return _marked(fitted, spans, len(text), style, style + self._styles.get("log-table--match", Style()))
        return [Segment(fitted, style)]

    def _badge_text(self, badge: StormBadge, width: int) -> str:
        """``×120 until 12:00:31.200`` on a storm's row when the message keeps half the cell,
        else ``×120 +30.1 s`` (the time from its first message to its last) when it keeps 8
        cells, else ``×120``; ``┆`` on the rows of an expanded storm."""
        if not badge.head:
            return "  ┆ "
        count = f"{'▾' if badge.expanded else ''}×{badge.repeats} "
        last, first = badge.last, badge.first
        if last in self.store:
            last_ns = self.store.stamp_of(last)
            marks = [(f"{count}until {clock_text(last_ns, utc=self.utc)}  ", max(12, width // 2))]
            if first in self.store:
                marks.append((f"{count}+{duration_text(max(last_ns - self.store.stamp_of(first), 0))} ", 8))
            for mark, room in marks:
                if width - len(mark) >= room:
                    return mark
        return count[: max(width - 1, 0)]

    def _cell_text(self, record: LogRecord, key: str, width: int) -> str:
        if key == "message":
            return one_line(record.msg, max(width * 2, 64) if width < _MESSAGE_LIMIT else _MESSAGE_LIMIT)
        if key == "seq":
            return str(record.seq + 1)
        if key == "time":
            return time_cell(record.stamp_ns, self.time_format, utc=self.utc)
        if key == "severity":
            return severity_name(record.level)
        if key == "node":
            return _node_text(record.node, width)
        if key == "file":
            return one_line(os.path.basename(record.file), 200)
        if key == "function":
            return one_line(record.function, 200)
        if key == "line":
            return str(record.line) if record.line else ""
        if key == "source":
            return one_line(os.path.basename(record.source.rstrip("/")) or record.source, 200)
        if key == "robot":
            return one_line(record.robot, 200)
        raise KeyError(key)


class _RowSegments:
    """A row's segments as they are added, each run of one style joined into one segment
    (what ``Strip.simplify`` would do after), and the cells counted: the row becomes one
    ``Strip`` of the table's width, without Textual's passes to measure, pad and join it."""

    __slots__ = ("_style", "_texts", "cells", "segments")

    def __init__(self) -> None:
        self.segments: list[Segment] = []
        self.cells = 0
        self._texts: list[str] = []
        self._style: Style | None = None

    def add(self, text: str, style: Style | None) -> None:
        """``text`` (already fitted: its length in cells is known when it is ASCII)."""
        if not text:
            return
        self.cells += len(text) if text.isascii() else cell_len(text)
        if style is not self._style and style != self._style:
            self._flush()
            self._style = style
        self._texts.append(text)

    def _flush(self) -> None:
        if self._texts:
            self.segments.append(Segment("".join(self._texts), self._style))
            self._texts = []

    def strip(self, width: int, style: Style) -> Strip:
        """The row, padded with ``style`` or cut to ``width`` cells."""
        if self.cells < width:
            self.add(" " * (width - self.cells), style)
        elif self.cells > width and self._texts:
            last, excess = self._texts[-1], self.cells - width
            if excess <= len(last) and last.isspace():  # the last column's separator
                self._texts[-1] = last[:-excess]
                self.cells = width
        self._flush()
        if self.cells > width:
            return Strip(self.segments, self.cells).crop(0, width)
        return Strip(self.segments, width)


@lru_cache(maxsize=4096)
def _node_text(node: str, width: int) -> str:
    return shorten_name(one_line(node, 200), width)


def _marked(fitted: str, spans: Spans, length: int, style: Style, marked: Style) -> list[Segment]:
    """``fitted`` (a cell's text cut or padded by ``fit``) with ``spans`` of the text before
    fitting (``length`` characters) in the ``marked`` style, as far as they are still shown."""
    shown = length if len(fitted) >= length and not fitted[length:].strip() else max(len(fitted) - 1, 0)
    segments: list[Segment] = []
    at = 0
    for start, end in spans:
        start, end = max(start, at), min(end, shown)
        if start >= end:
            continue
        if start > at:
            segments.append(Segment(fitted[at:start], style))
        segments.append(Segment(fitted[start:end], marked))
        at = end
    segments.append(Segment(fitted[at:], style))
    return segments


def fit(text: str, width: int, align: str = "left") -> str:
    """Exactly ``width`` cells: padded, or cut with an ellipsis."""
    length = len(text) if text.isascii() else cell_len(text)
    if length > width:
        return set_cell_size(text, max(width - 1, 0)) + ("…" if width else "")
    if align == "right":
        return " " * (width - length) + text
    return text + " " * (width - length)
