"""How the log table draws one row, and its header: a record's cells fitted to the columns'
widths and styled (severity, the row's look: rules, cursor, selection, storm counts, the
gutter's mark, search matches) into a ``Strip``; and the columns laid out for a width (which
are shown, how wide the node column is, what the Time column shows), again only when one of
them or the width changed (the columns themselves, and how they share the width:
``table_columns.py``).

A plain object (``RowPainter``) the table owns: it reads only what it is given, the store for
the records' strings and the component styles the table looks up.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from functools import lru_cache

from rich.cells import cell_len, set_cell_size
from rich.segment import Segment
from rich.style import Style
from textual.strip import Strip

from ...model.inert_text import one_line, shorten_name
from ...model.levels import severity_level, severity_name
from ...model.overview.storms import StormBadge
from ...model.store.log_store import LogStore
from ...model.store.record import LogRecord
from ...model.time_column import TimeFormat, column_title, format_info, time_cell
from ...model.timefmt import clock_text, duration_text
from ..severity_styles import severity_classes, severity_css
from .row_decorations import RowLook, Spans
from .table_columns import COLUMNS, PlacedColumn, layout_columns

#: Cells of the gutter (a mark, and a space).
GUTTER = 2
_MESSAGE_LIMIT = 2000
_NO_STYLE = Style()


#: The table's looks: the rows' styles by their component classes (``LogTable`` takes these).
ROW_CSS = (
    """
    LogTable {
        background: $surface;
        color: $foreground;
        scrollbar-gutter: stable;
    }
    LogTable > .log-table--header { text-style: bold; background: $panel; color: $foreground; }
    LogTable > .log-table--cursor { background: $block-cursor-blurred-background; }
    LogTable:focus > .log-table--cursor { background: $block-cursor-background; color: $block-cursor-foreground; }
    LogTable > .log-table--dim-column { color: $foreground-muted; }
    LogTable > .log-table--selected { background: $primary-muted; }
    LogTable > .log-table--highlight { background: $accent-muted; }
    LogTable > .log-table--dimmed { text-style: dim; }
    LogTable > .log-table--storm { color: $text-accent; text-style: bold; }
    LogTable > .log-table--match { background: $warning; color: $background; text-style: bold; }
    LogTable > .log-table--gutter { color: $text-accent; text-style: bold; }
"""
    + severity_css("LogTable", "log-table--row", row=True)
    + severity_css("LogTable", "log-table--severity")
)

ROW_CLASSES = {
    "log-table--header",
    "log-table--cursor",
    "log-table--selected",
    "log-table--dim-column",
    *severity_classes("log-table--row"),
    *severity_classes("log-table--severity"),
    "log-table--highlight",
    "log-table--dimmed",
    "log-table--storm",
    "log-table--match",
    "log-table--gutter",
}


class RowPainter:
    """The columns as laid out, and the strips of the header and of one row."""

    def __init__(self, store: LogStore, *, utc: bool = False) -> None:
        self.store = store
        self.utc = utc
        #: What the Time column shows (``t``), in local time or UTC.
        self.time_format = TimeFormat.CLOCK
        self.shown_columns: frozenset[str] = frozenset(c.key for c in COLUMNS if c.shown_by_default)
        #: A fleet's robots' colours (``--fleet``'s ``colour``) by name, for the Robot column.
        self.robot_styles: dict[str, Style] = {}
        #: The table's component styles by class name (it looks them up once a frame).
        self.styles: dict[str, Style] = {}
        self.placed: tuple[PlacedColumn, ...] = ()
        self._layout_key: tuple = ()
        self._nodes_measured = 0
        self._widest_node = 8

    def set_column_shown(self, key: str, shown: bool) -> None:
        columns = set(self.shown_columns)
        (columns.add if shown else columns.discard)(key)
        columns.add("message")
        self.shown_columns = frozenset(columns)

    def layout(self, width: int, gutter: bool) -> bool:
        """Lay the columns out for ``width`` cells (and a gutter); True when they moved."""
        store = self.store
        nodes = store.nodes
        if len(nodes) != self._nodes_measured:
            self._nodes_measured = len(nodes)
            self._widest_node = max((cell_len(name) for name in nodes), default=8)
        # Wide enough for most names whole (20 of 80 columns, 24 of 100, 32 of 160); longer
        # ones are shortened from the front, keeping the end that tells them apart (shorten_name).
        node_width = max(min(self._widest_node, max(24, width // 5), max((width + 3) // 4, 12)), 6)
        cells = GUTTER if gutter else 0
        # A fleet's robots: as wide as the widest name, 5 to 16 cells.
        robot_width = max(min(max(map(cell_len, store.robots), default=5), 16), 5)
        key = (width, self.shown_columns, node_width, cells, self.time_format, self.utc, robot_width)
        if key == self._layout_key:
            return False
        self._layout_key = key
        widths = {"time": format_info(self.time_format).width, "robot": robot_width}
        self.placed = layout_columns(width - cells, self.shown_columns, node_width, widths)
        return True

    @property
    def layout_key(self) -> tuple:
        return self._layout_key

    def header(self, width: int, base: Style, gutter: bool) -> Strip:
        style = base + self.styles.get("log-table--header", _NO_STYLE)
        segments: list[Segment] = []
        if gutter:
            segments.append(Segment(" " * GUTTER, style))
        for place in self.placed:
            title = column_title(self.time_format, self.utc) if place.column.key == "time" else place.column.title
            segments.append(Segment(fit(title, place.width, place.column.align) + " ", style))
        return Strip(segments).adjust_cell_length(width, style)

    def row(
        self, record: LogRecord, width: int, base: Style, look: RowLook, matches: Callable[[int, str], Spans] | None
    ) -> Strip:
        """The row of ``record`` as ``look`` says, ``matches`` marking where a search matches."""
        styles = self.styles
        is_cursor, decoration, badge, gutter = look.cursor, look.decoration, look.badge, look.gutter
        name = severity_level(record.level).style
        row_style = base + styles.get(f"log-table--row-{name}", Style())
        if decoration == "highlight":
            row_style += styles.get("log-table--highlight", Style())
        elif decoration == "dim":
            row_style += styles.get("log-table--dimmed", Style())
        if look.selected:
            row_style += styles.get("log-table--selected", Style())
        if is_cursor:
            row_style += styles.get("log-table--cursor", Style())
        muted = styles.get("log-table--dim-column", Style())
        row = _RowSegments()
        add = row.add
        if gutter is not None:
            add(fit(gutter, 1), row_style + styles.get("log-table--gutter", Style()))
            add(" ", row_style)
        for place in self.placed:
            key = place.column.key
            if key == "message" and badge is not None:
                mark = self._badge_text(badge, place.width)
                add(mark, row_style + styles.get("log-table--storm", Style()))
                room = place.width - len(mark)
                text = self._cell_text(record, key, room)
                for segment in self._message_segments(matches, record.seq, text, fit(text, room), row_style):
                    add(*segment[:2])
                add(" ", row_style)
                continue
            if key == "time":
                text = time_cell(
                    record.stamp_ns,
                    self.time_format,
                    utc=self.utc,
                    origin_ns=look.relative,
                    previous_ns=look.relative,
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
                for segment in self._message_segments(matches, record.seq, text, fitted, style):
                    add(*segment[:2])
            else:
                add(fitted, style)
            add(" ", row_style)
        return row.strip(width, row_style)

    def _message_segments(
        self, matches: Callable[[int, str], Spans] | None, seq: int, text: str, fitted: str, style: Style
    ) -> list[Segment]:
        """The message cell, with where a search matches marked."""
        spans = matches(seq, text) if matches is not None else None
        if spans:
            return _marked(fitted, spans, len(text), style, style + self.styles.get("log-table--match", Style()))
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
