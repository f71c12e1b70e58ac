"""How the log table draws a frame: the styles and columns worked out once a frame, the rows
on screen from a cache of rows drawn (by seq and how they are marked), and the last frame's
strips given again when nothing on screen changed.

A part of ``LogTable`` (it mixes this in); the strips of rows not cached come from
``log_table_cells.py``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from rich.segment import Segment
from rich.style import Style
from textual.cache import LRUCache
from textual.geometry import Region, Spacing
from textual.strip import Strip

from ...model.inert_text import one_line
from ...model.overview.storms import StormBadge
from ...model.time_column import TimeFormat
from .log_table_cells import Decoration, TableCells, fit
from .log_table_layout import TableLayout

if TYPE_CHECKING:
    from .table_rows import TableRows

_NO_SPACING = Spacing(0, 0, 0, 0)


class TableFrame(TableLayout, TableCells):
    """``render_lines`` and ``render_line`` with their caches (``LogTable`` mixes this in)."""

    # What it reads of the table (``LogTable`` sets them) beside what its bases read.
    view: TableRows
    cursor_row: int
    selection_anchor: int | None
    decoration_of: Callable[[int], Decoration] | None
    badge_of: Callable[[int], StormBadge | None] | None
    style_generation: int
    empty_hint: str
    selected_rows: Callable[[], range]
    _shown_seqs: Callable[[int], tuple[object, ...]]
    # Its own (``LogTable.__init__`` sets them first).
    _cache: LRUCache[tuple, Strip]
    _base: Style
    _styles_key: tuple | None
    _width: int
    _frame: tuple[tuple, list[Strip]] | None

    if TYPE_CHECKING:  # ``LogTable``'s properties

        @property
        def row_count(self) -> int: ...
        @property
        def cursor_seq(self) -> int | None: ...

    def _forget_drawn_rows(self) -> None:
        self._cache.clear()
        self._frame = None

    def restyle(self) -> None:
        """Decorations changed (rules): drop cached rows and redraw."""
        self.style_generation += 1
        self._forget_drawn_rows()
        self.refresh()

    def notify_style_update(self) -> None:
        super().notify_style_update()
        self._styles_key = None

    def _look_up_styles(self) -> None:
        """Component styles, looked up again only when the focus, the theme or the CSS changed
        (the lookups cost more than drawing a row); rows drawn in old styles are dropped."""
        key = (self.has_focus, self.app.theme)
        if key != self._styles_key:
            self._styles_key = key
            styles = {name: self.get_component_rich_style(name, partial=True) for name in self.COMPONENT_CLASSES}
            base = self.rich_style
            changed = {name for name in styles if styles[name] != self._styles.get(name)}
            self._styles, self._frame = styles, None
            if base != self._base or changed - {"log-table--cursor"}:
                self._base = base
                self._forget_drawn_rows()
            elif changed:  # focus came or went: only the cursor's row looks different
                cursor_rows = [row_key for row_key in list(self._cache.keys()) if row_key[1]]
                for row_key in cursor_rows:  # (the key's second item: the cursor's row)
                    self._cache.discard(row_key)

    def render_lines(self, crop: Region) -> list[Strip]:
        # Everything a row needs that is the same for every row: worked out once a frame.
        self._look_up_styles()
        self._width = self.scrollable_content_region.width
        self._layout(self._width)
        if self.styles.padding != _NO_SPACING or self.styles.border.spacing != _NO_SPACING:
            return super().render_lines(crop)
        # No border or padding to draw: the rows go straight to the screen (with the app's
        # line filters), which saves Textual's per-line styling work on every frame; at
        # thousands of messages a second every visible row is new in every frame.
        filters = self.get_line_filters()
        background = self.background_colors[1]
        full_width = self.size.width  # the scrollbar gutter too, when no scrollbar covers it
        # Textual redraws every widget under a changed region (the scrollbar, a notification):
        # the same rows in the same styles give the same strips as last time.
        frame_key = (
            crop,
            full_width,
            self._shown_seqs(int(self.scroll_y)),
            self.selection_anchor,
            self.style_generation,
            self._styles_key,
            self._layout_key,
            background,
            self.empty_hint if not self.row_count else "",
            *map(id, filters),
        )
        if self._frame is not None and self._frame[0] == frame_key:
            return self._frame[1]
        strips = []
        for y in crop.line_range:
            strip = self.render_line(y)
            if strip.cell_length < full_width:
                strip = strip.extend_cell_length(full_width, self._base)
            for line_filter in filters:
                strip = strip.apply_filter(line_filter, background)
            strips.append(strip)
        x1, x2 = crop.column_span
        if (x1, x2) != (0, full_width):
            strips = [strip.crop(x1, x2) for strip in strips]
        self._frame = (frame_key, strips)
        return strips

    def render_line(self, y: int) -> Strip:
        width, base, placed = self._width, self._base, self._placed
        if y == 0:
            return self._header(placed, width, base)
        row = int(self.scroll_y) + y - 1
        if row >= self.row_count:
            if y == 2 and not self.row_count and self.empty_hint:
                style = base + self._styles.get("log-table--dim-column", Style())
                return Strip([Segment(fit("  " + one_line(self.empty_hint, 400), width), style)], width)
            return Strip.blank(width, base)
        seq = self.view.seq_at(row)
        is_cursor = row == self.cursor_row
        selected = self.selection_anchor is not None and row in self.selected_rows()
        decoration = self.decoration_of(seq) if self.decoration_of is not None else None
        badge = self.badge_of(seq) if self.badge_of is not None else None
        gutter = self.gutter_of(seq) if self.gutter_of is not None else None
        relative = self._relative_time(row) if self.time_format.relative else None
        key = (seq, is_cursor, selected, decoration, self.style_generation, badge, gutter, relative)
        strip = self._cache.get(key)
        if strip is None:
            record = self.store.get(seq)
            strip = self._render_row(
                record, placed, width, base, is_cursor, selected, decoration, badge, gutter, relative
            )
            self._cache[key] = strip
        return strip

    def _relative_time(self, row: int) -> int | None:
        """The stamp a relative Time cell counts from: the first message's, the selected
        row's, or the row above's (None for the first row)."""
        fmt = self.time_format
        if fmt is TimeFormat.DELTA:
            return self.store.get(self.view.seq_at(row - 1)).stamp_ns if row > 0 else None
        seq = self.store.first_seq if fmt is TimeFormat.SINCE_FIRST else self.cursor_seq
        return self.store.get(seq).stamp_ns if seq is not None and seq in self.store else None
