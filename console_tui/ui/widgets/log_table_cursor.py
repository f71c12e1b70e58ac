"""The log table's cursor and the rows selected with it: moving by keys and clicks, jumping
to a record's row (or the one nearest it in time), and which rows (and seqs) are selected.

A part of ``LogTable`` (it mixes this in).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from textual import events
from textual.actions import SkipAction
from textual.message import Message
from textual.scroll_view import ScrollView

if TYPE_CHECKING:
    from ...model.store import LogStore
    from .table_rows import TableRows


class TableCursor(ScrollView):
    """The cursor's row, the selection's anchor, and the keys that move them (``LogTable``
    mixes this in)."""

    # What it reads of the table (``LogTable`` sets them).
    store: LogStore
    view: TableRows
    following: bool
    paused_end: int | None
    cursor_row: int
    selection_anchor: int | None
    _stop_following: Callable[[], None]
    StateChanged: type[Message]
    TopReached: type[Message]
    action_activate: Callable[[], None]

    if TYPE_CHECKING:  # ``LogTable``'s properties

        @property
        def row_count(self) -> int: ...
        @property
        def cursor_seq(self) -> int | None: ...
        @property
        def _body_height(self) -> int: ...

    def move_cursor(self, row: int, *, extend: bool = False) -> None:
        """Move the cursor to ``row``; ``extend`` selects the rows from where it was."""
        rows = self.row_count
        if row < 0 and self.cursor_row == 0:
            self.post_message(self.TopReached())  # older rows may be asked for
        if rows == 0:
            return
        if not extend:
            self.selection_anchor = None
        elif self.selection_anchor is None:
            self.selection_anchor = self.cursor_seq
        row = min(max(row, 0), rows - 1)
        self.cursor_row = row
        top = int(self.scroll_y)
        height = self._body_height
        if row < top:
            self.set_scroll(None, row)
        elif row >= top + height:
            self.set_scroll(None, row - height + 1)
        if row < rows - 1:
            self._stop_following()
        elif self.paused_end is None:
            self.following = True
        self.refresh()
        self.post_message(self.StateChanged())

    def _place_of(self, seq: int, nearest: bool) -> int:
        """The row of ``seq``; when no row shows it, the next row, or (``nearest``) the
        row nearest it in time."""
        view, store = self.view, self.store
        if not nearest:
            return view.row_of(seq)
        shown = view.row_shown(seq)
        if shown is not None:
            return shown
        after = view.row_of(seq)
        if after == 0 or after >= self.row_count or seq not in store:
            return after
        stamp = store.stamp_of(seq)
        before_gap = stamp - store.stamp_of(view.seq_at(after - 1))
        after_gap = store.stamp_of(view.seq_at(after)) - stamp
        return after - 1 if before_gap <= after_gap else after

    def jump_to_seq(self, seq: int) -> bool:
        """Put the cursor on the row of ``seq`` (a third down the screen when it was off the
        screen; a collapsed repeat's is its storm's row); False when no row shows it."""
        row = self.view.row_shown(seq)
        if row is None or row >= self.row_count:
            return False
        height = self._body_height
        top = int(self.scroll_y)
        if not top <= row < top + height:
            self._stop_following()
            self.set_scroll(None, max(min(row - height // 3, self.row_count - height), 0))
        self.move_cursor(row)
        return True

    def selected_rows(self) -> range:
        """The selected rows (the cursor's alone when nothing else is selected)."""
        if self.row_count == 0:
            return range(0)
        anchor = self.cursor_row if self.selection_anchor is None else self.view.row_of(self.selection_anchor)
        anchor = min(anchor, self.row_count - 1)
        return range(min(anchor, self.cursor_row), max(anchor, self.cursor_row) + 1)

    def selected_seqs(self, at_most: int) -> list[int]:
        """The seqs of the selected rows, the first ``at_most`` of them."""
        rows = self.selected_rows()
        return [self.view.seq_at(row) for row in rows[:at_most]]

    def action_cursor_up(self) -> None:
        self.move_cursor(self.cursor_row - 1)

    def action_cursor_down(self) -> None:
        self.move_cursor(self.cursor_row + 1)

    def action_select_up(self) -> None:
        self.move_cursor(self.cursor_row - 1, extend=True)

    def action_select_down(self) -> None:
        self.move_cursor(self.cursor_row + 1, extend=True)

    def action_clear_selection(self) -> None:
        if self.selection_anchor is None:
            raise SkipAction()  # Esc goes on to the app (it stops a long filtering)
        self.selection_anchor = None
        self.refresh()

    def action_page_up(self) -> None:
        self.move_cursor(self.cursor_row - self._body_height)

    def action_page_down(self) -> None:
        self.move_cursor(self.cursor_row + self._body_height)

    def action_first_row(self) -> None:
        self.move_cursor(-1 if self.cursor_row == 0 else 0)

    def _row_at(self, y: int) -> int | None:
        if y < 1:
            return None
        row = int(self.scroll_y) + y - 1
        return row if row < self.row_count else None

    async def _on_click(self, event: events.Click) -> None:
        row = self._row_at(event.y)
        if row is None:
            return
        self.move_cursor(row, extend=event.shift)
        if event.chain >= 2:
            self.action_activate()
