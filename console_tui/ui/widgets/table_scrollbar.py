"""The log table's vertical scrollbar: redrawn only when what it shows changes.

Textual's ``ScrollBar`` redraws itself whenever the scrolled widget's height, the window or
the position change. While the table follows a long history's tail, the height changes on
every drain of the intake, but the thumb stays one cell at the bottom: each redraw (about
1.5 ms, a frame's longest part after the rows) drew the same column. This one keeps the
values exact (a click or a drag reads them) and redraws only when the thumb's cells, to an
eighth of a cell as Textual draws them, are not the same.
"""

from __future__ import annotations

from math import ceil

from rich.console import RenderableType
from textual.reactive import Reactive
from textual.scrollbar import ScrollBar, ScrollBarRender

#: Textual draws a thumb's ends in eighths of a cell.
_EIGHTHS = len(ScrollBarRender.VERTICAL_BARS)


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
