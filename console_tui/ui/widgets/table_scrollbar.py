"""The log table's vertical scrollbar: redrawn only when what it shows changes; and the
``ScrollView`` that has one (``RowsScrollView``, the table's base), whose height changes
without a layout of the screen.

It keeps the values exact (a click or a drag reads them) and redraws only when the thumb's cells,
to an eighth of a cell as Textual draws them, are not the same: while the table follows a long
history's tail its height changes on every drain of the intake, but the thumb stays one cell at
the bottom. A redraw makes the column's lines straight from Textual's own
``ScrollBarRender.render_bar`` (one segment a row) and keeps them until the next refresh, instead
of going through Rich's rendering and Textual's styles cache. Why, and the figures:
docs/decisions/0018-own-widgets.md.
"""

from __future__ import annotations

from math import ceil
from typing import Literal

from rich.color import Color
from rich.console import RenderableType
from rich.segment import Segment
from rich.style import Style
from textual.geometry import Region, Size
from textual.reactive import Reactive
from textual.scroll_view import ScrollView
from textual.scrollbar import ScrollBar, ScrollBarRender
from textual.strip import Strip

#: Textual draws a thumb's ends in eighths of a cell.
_EIGHTHS = len(ScrollBarRender.VERTICAL_BARS)
#: How often the scrollbar follows changes that leave the rows on screen as they were (s).
_QUIET_SCROLLBAR_PERIOD = 0.1


class TableScrollBar(ScrollBar):
    """A ``ScrollBar`` that repaints only when its thumb moves or changes size."""

    window_virtual_size: Reactive[int] = Reactive(100, repaint=False)
    window_size: Reactive[int] = Reactive(0, repaint=False)
    position: Reactive[float] = Reactive(0, repaint=False)

    def __init__(self, vertical: bool = True, name: str | None = None, *, thickness: int = 1) -> None:
        super().__init__(vertical, name, thickness=thickness)
        #: The thumb last drawn (``thumb``), and whether a check that it moved is queued.
        self._drawn: tuple[int, ...] | None = None
        self._check_due = False
        #: Every row as last drawn (``_draw_rows``), until the next refresh.
        self._rows: list[Strip] | Literal[False] | None = None

    def thumb(self) -> tuple[int, ...]:
        """The length of the bar and the thumb's first and last eighth of a cell, as
        ``ScrollBarRender.render_bar`` works them out; the length alone when no thumb."""
        size = self.size.height if self.vertical else self.size.width
        virtual = ceil(self.window_virtual_size)
        window = ceil(self.window_size) if self.window_size < self.window_virtual_size else 0
        if not (window and size and virtual and size != virtual):
            return (size,)
        thumb_size = max(1, window / (virtual / size))
        position = (size - thumb_size) * (self.position / (virtual - window))
        start = int(position * _EIGHTHS)
        return (size, start, start + ceil(thumb_size * _EIGHTHS))

    def render(self) -> RenderableType:
        self._drawn = self.thumb()
        return super().render()

    def render_lines(self, crop: Region) -> list[Strip]:
        # Textual's own lines, less the trip through Rich and its styles cache: the column as
        # ``render_bar`` makes it, one segment a row over the widget's style, made again only
        # after a refresh (the compositor asks for a few rows at a time, often).
        if self._dirty_regions or self._rows is None:
            self._rows = self._draw_rows()
            if self._rows is not False:  # (else Textual draws it, and reads what changed)
                self._dirty_regions.clear()
        if self._rows is False:
            return super().render_lines(crop)
        rows = self._rows[crop.y : crop.bottom]
        filters = self.get_line_filters()
        if filters:
            _, background = self.background_colors
            for line_filter in filters:
                rows = [row.apply_filter(line_filter, background) for row in rows]
        if crop.column_span != (0, self.size.width):
            rows = [row.crop(crop.x, crop.right) for row in rows]
        return rows

    def _draw_rows(self) -> list[Strip] | Literal[False]:
        """Every row of the bar; ``False`` when it is not a plain vertical bar (Textual draws it)."""
        bar = self.render()
        style = getattr(bar, "style", None)
        if not (self.vertical and isinstance(bar, ScrollBarRender) and isinstance(style, Style)):
            return False
        width, height = self.size
        column = ScrollBarRender.render_bar(
            size=height,
            virtual_size=bar.virtual_size,
            window_size=bar.window_size,
            position=bar.position,
            thickness=width,
            vertical=True,
            back_color=style.bgcolor or Color.parse("#555555"),
            bar_color=style.color or Color.parse("bright_magenta"),
        )
        base = self.visual_style.rich_style  # under each segment's own style, as Rich's rendering puts it
        return [Strip((Segment(segment.text, base + segment.style),), width) for segment in column.segments]

    def _thumb_may_have_moved(self) -> None:
        # Checked once all of an update's values are set (height, window, position: one
        # after the other, and the thumb in between is not one to draw).
        if not self._check_due:
            self._check_due = True
            self.call_next(self._repaint_if_moved)

    def _repaint_if_moved(self) -> None:
        self._check_due = False
        if self.thumb() != self._drawn:
            self.refresh()

    def watch_window_virtual_size(self) -> None:
        self._thumb_may_have_moved()

    def watch_window_size(self) -> None:
        self._thumb_may_have_moved()

    def watch_position(self) -> None:
        self._thumb_may_have_moved()


class RowsScrollView(ScrollView):
    """A ``ScrollView`` with a ``TableScrollBar``, whose height (rows arriving, many times a
    second) changes without asking for a layout of the screen."""

    _scrollbar_sync_due = False

    @property
    def vertical_scrollbar(self) -> ScrollBar:
        """Textual's own code, with a ``TableScrollBar``: repainted only when its thumb moves."""
        if self._vertical_scrollbar is None:
            bar = TableScrollBar(vertical=True, name="vertical", thickness=self.scrollbar_size_vertical)
            bar.display = False
            self._vertical_scrollbar = bar
            self.app._start_widget(self, bar)
        return self._vertical_scrollbar

    def _scroll_update(self, virtual_size: Size) -> None:
        """Textual's, less its repaint of the vertical scrollbar on every call: the
        ``TableScrollBar`` repaints itself when its thumb moves."""
        self._refresh_scrollbars()
        width, height = self.container_size
        if self.show_vertical_scrollbar and self.styles.scrollbar_size_vertical:
            self.vertical_scrollbar.window_virtual_size = virtual_size.height
            self.vertical_scrollbar.window_size = height - self.scrollbar_size_horizontal
        if self.show_horizontal_scrollbar and self.styles.scrollbar_size_horizontal:
            self.horizontal_scrollbar.window_virtual_size = virtual_size.width
            self.horizontal_scrollbar.window_size = width - self.scrollbar_size_vertical
            self.horizontal_scrollbar.refresh()
        self.scroll_x = self.validate_scroll_x(self.scroll_x)
        self.scroll_y = self.validate_scroll_y(self.scroll_y)

    def set_scroll(self, x: float | None, y: float | None) -> None:
        """Textual's, and the scrollbar told (Textual's sets the offset alone)."""
        super().set_scroll(x, y)
        if y is not None and self.show_vertical_scrollbar:
            self.vertical_scrollbar.position = self.scroll_y

    def set_height(self, height: int, *, quiet: bool = False) -> None:
        """The rows' height (the header's line included); ``quiet`` (the rows on screen stay
        as they were) tells the scrollbar only a few times a second."""
        size = Size(self.scrollable_content_region.width, height)
        if size != self.virtual_size:
            # Not ``self.virtual_size = size``: that reactive asks for a layout of the whole
            # screen, many times a second while messages arrive. Only the scrollbars change.
            self.set_reactive(ScrollView.virtual_size, size)
            if not quiet:
                self._scroll_update(size)
        if quiet and not self._scrollbar_sync_due:
            self._scrollbar_sync_due = True
            self.set_timer(_QUIET_SCROLLBAR_PERIOD, self._sync_scrollbars)

    def _sync_scrollbars(self) -> None:
        """Scrollbars to the virtual size and scroll offset (redrawing the scrollbar region
        redraws every widget under it, the table included)."""
        self._scrollbar_sync_due = False
        self._scroll_update(self.virtual_size)
        if self.show_vertical_scrollbar:
            self.vertical_scrollbar.position = self.scroll_y
