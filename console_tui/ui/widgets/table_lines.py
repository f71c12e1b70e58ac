"""The log table's lines as strips: the header, the rows, the hint of an empty table, from the
rows kept drawn (an LRU by seq and how the row looks) and the last frame given again when
nothing on screen changed. A plain object the table owns; the table says which rows are on
screen and where the cursor is, the painter draws what is not kept.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable

from rich.segment import Segment
from rich.style import Style
from textual.cache import LRUCache
from textual.geometry import Region
from textual.strip import Strip

from ...model.inert_text import one_line
from ...model.store.log_store import LogStore
from ...model.time_column import TimeFormat
from .row_decorations import RowDecorations
from .row_painter import RowPainter, fit
from .table_cursor import TableCursor
from .table_rows import TableRows

#: Rows kept drawn, for scrolling back over them. A few screens: each is a dozen objects for
#: the cycle collector to visit (benchmarks/screen.py: 512 rows cost about a fifth more per
#: full collection than 192).
KEPT_ROWS = 192


class TableLines:
    """The strips of the table's lines, and what they were drawn from."""

    def __init__(self, store: LogStore, painter: RowPainter, decorations: RowDecorations) -> None:
        self.store = store
        self.painter = painter
        self.decorations = decorations
        #: Bumped when rows look different (``restyled``): part of every kept row's key.
        self.generation = 0
        #: The style under every row (the table's own).
        self.base = Style()
        self._rows: LRUCache[tuple, Strip] = LRUCache(KEPT_ROWS)
        #: The last frame's strips, and what they were drawn from.
        self._frame: tuple[Hashable, list[Strip]] | None = None

    def forget(self) -> None:
        """Every row is drawn again (the columns, the styles or the records changed)."""
        self._rows.clear()
        self._frame = None

    def restyled(self) -> None:
        """The decorations changed: every row is drawn again."""
        self.generation += 1
        self.forget()

    def set_styles(self, styles: dict[str, Style], base: Style) -> None:
        """The table's component styles looked up again (the focus, the theme or the CSS
        changed): rows drawn in other styles are dropped, only the cursor's when only its
        style changed (the focus came or went)."""
        old = self.painter.styles
        changed = {name for name in styles if styles[name] != old.get(name)}
        self.painter.styles, self._frame = styles, None
        if base != self.base or changed - {"log-table--cursor"}:
            self.base = base
            self.forget()
        elif changed:
            for key in [key for key in list(self._rows.keys()) if key[1].cursor]:  # (seq, look, ...)
                self._rows.discard(key)

    def frame(
        self,
        key: Hashable,
        crop: Region,
        width: int,
        filters: Iterable[object],
        background: object,
        line: Callable[[int], Strip],
    ) -> list[Strip]:
        """The strips of ``crop``'s lines, ``width`` cells wide with the line filters applied;
        the last frame's when ``key`` (what is on screen, and how) is the same."""
        if self._frame is not None and self._frame[0] == key:
            return self._frame[1]
        strips = []
        for y in crop.line_range:
            strip = line(y)
            if strip.cell_length < width:
                strip = strip.extend_cell_length(width, self.base)
            for line_filter in filters:
                strip = strip.apply_filter(line_filter, background)  # type: ignore[arg-type]
            strips.append(strip)
        x1, x2 = crop.column_span
        if (x1, x2) != (0, width):
            strips = [strip.crop(x1, x2) for strip in strips]
        self._frame = (key, strips)
        return strips

    def line(
        self, y: int, *, top: int, rows: TableRows, count: int, cursor: TableCursor, width: int, hint: str
    ) -> Strip:
        """Line ``y`` (0: the header) with row ``top`` under the header, ``count`` rows shown."""
        base, decorations = self.base, self.decorations
        if y == 0:
            return self.painter.header(width, base, gutter=decorations.gutter is not None)
        row = top + y - 1
        if row >= count:
            if y == 2 and not count and hint:
                style = base + self.painter.styles.get("log-table--dim-column", Style())
                return Strip([Segment(fit("  " + one_line(hint, 400), width), style)], width)
            return Strip.blank(width, base)
        seq = rows.seq_at(row)
        selected = cursor.anchor is not None and row in cursor.selected_rows(rows, count)
        relative = (
            self._relative_time(row, rows, cursor.seq(rows, count)) if self.painter.time_format.relative else None
        )
        look = decorations.look(seq, row == cursor.row, selected, relative)
        key = (seq, look, self.generation)
        strip = self._rows.get(key)
        if strip is None:
            strip = self.painter.row(self.store.get(seq), width, base, look, decorations.matches)
            self._rows[key] = strip
        return strip

    def _relative_time(self, row: int, rows: TableRows, cursor_seq: int | None) -> int | None:
        """The stamp a relative Time cell counts from: the first message's, the selected
        row's, or the row above's (None for the first row)."""
        store, fmt = self.store, self.painter.time_format
        if fmt is TimeFormat.DELTA:
            return store.get(rows.seq_at(row - 1)).stamp_ns if row > 0 else None
        seq = store.first_seq if fmt is TimeFormat.SINCE_FIRST else cursor_seq
        return store.get(seq).stamp_ns if seq is not None and seq in store else None
