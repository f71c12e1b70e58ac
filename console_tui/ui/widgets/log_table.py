"""The log table: a line-API view over the store that renders only the visible rows.

Rows are addressed by store seq, which never changes, so rendered rows are cached by seq
and the position survives records arriving and old ones being evicted. Line 0 is a fixed
header; line ``y`` shows row ``scroll_y + y - 1``.

The widget holds which rows it shows and where (following the tail, the pause, keeping its
place as records come and go), draws a frame from the rows it keeps drawn, and composes plain
objects for the rest: the cursor and the selection (``table_cursor.py``), the columns and one
row's cells (``row_painter.py``), and how rows are marked beyond their records, which the
rules, the overview, the search and the marks contribute to (``row_decorations.py``).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from textual import events
from textual.actions import SkipAction
from textual.binding import Binding
from textual.geometry import Region, Spacing
from textual.message import Message
from textual.scroll_view import ScrollView
from textual.strip import Strip

from ...model.store.log_store import LogStore
from ...model.time_column import TimeFormat
from .row_decorations import Decoration, RowDecorations, Spans
from .row_painter import ROW_CLASSES, ROW_CSS, RowPainter
from .table_cursor import TableCursor, place_of
from .table_lines import TableLines
from .table_rows import TableRows
from .table_scrollbar import RowsScrollView

_NO_SPACING = Spacing(0, 0, 0, 0)


class LogTable(RowsScrollView, can_focus=True):
    """Rows of a ``LogView`` (or ``StormRows``); follows the tail until the user moves away or pauses.

    | Key(s) | Description |
    | :- | :- |
    | up, k / down, j | Move the cursor. |
    | shift+up, K / shift+down, J | Select rows upwards / downwards. |
    | escape | Clear the selection. |
    | pageup / pagedown | A page up / down. |
    | home, g | The first row. |
    | end, G | Follow the tail. |
    | enter | Details of the row (``RowActivated``). |

    | Class | Description |
    | :- | :- |
    | `log-table--header` | The header row. |
    | `log-table--cursor` | The cursor's row. |
    | `log-table--selected` | Rows selected with shift+arrows. |
    | `log-table--dim-column` | Columns of lesser weight (number, time, location, source). |
    | `log-table--row-debug` ... `log-table--row-fatal` | A row, by its severity. |
    | `log-table--severity-debug` ... `log-table--severity-fatal` | The severity cell, by severity. |
    | `log-table--highlight` | Rows a highlight rule marks. |
    | `log-table--dimmed` | The other rows while highlighting. |
    | `log-table--storm` | The count of a storm's row (``×120 until ...``). |
    | `log-table--match` | Where a search matches, in the message. |
    | `log-table--gutter` | The gutter's marks: ● a mark, » a search match. |
    """

    DEFAULT_CSS = ROW_CSS
    COMPONENT_CLASSES = ROW_CLASSES

    BINDINGS = [
        Binding("up,k", "cursor_up", "Up", show=False, id="table.up"),
        Binding("down,j", "cursor_down", "Down", show=False, id="table.down"),
        Binding("shift+up,K", "select_up", "Select rows upwards", show=False, id="table.select_up"),
        Binding("shift+down,J", "select_down", "Select rows downwards", show=False, id="table.select_down"),
        Binding("escape", "clear_selection", "Clear the selection", show=False, id="table.clear_selection"),
        Binding("pageup", "page_up", "Page up", show=False, id="table.page_up"),
        Binding("pagedown", "page_down", "Page down", show=False, id="table.page_down"),
        Binding("home,g", "first_row", "First", show=False, id="table.first"),
        Binding("end,G", "follow", "Follow tail", id="table.follow"),
        Binding("enter", "activate", "Details", id="table.details"),
    ]

    @dataclass
    class RowActivated(Message):
        """Enter or a double click on a row."""

        seq: int

    class TopReached(Message):
        """The cursor was asked to go above the oldest row (up, page up or home on it)."""

        def can_replace(self, message: Message) -> bool:
            return isinstance(message, LogTable.TopReached)

    class StateChanged(Message):
        """Following, pause or cursor changed (for the status bar)."""

        def can_replace(self, message: Message) -> bool:
            return isinstance(message, LogTable.StateChanged)  # it says nothing but "look again"

    def __init__(
        self,
        store: LogStore,
        view: TableRows,
        *,
        utc: bool = False,
        decorations: RowDecorations | None = None,
        id: str | None = None,
    ) -> None:
        super().__init__(id=id)
        self.store = store
        self.view = view
        self.following = True
        #: While paused, rows for seqs at or past this are not shown.
        self.paused_end: int | None = None
        self.cursor = TableCursor()
        self.painter = RowPainter(store, utc=utc)
        #: How rows are marked beyond their records (the rules, storms, the search, the marks):
        #: every row is drawn again when it says they changed.
        self.decorations = decorations if decorations is not None else RowDecorations()
        self.decorations.subscribe(self.restyle)
        #: The lines drawn, and the rows kept drawn.
        self.lines = TableLines(store, self.painter, self.decorations)
        #: Said in the empty table (``show_hint``): what the console waits for, or that rules
        #: hide every message.
        self.empty_hint = ""
        self._styles_key: tuple | None = None
        self._width = 0

    def show_hint(self, hint: str) -> None:
        """Say ``hint`` in the table while it has no row (redrawn only when it changes)."""
        if hint != self.empty_hint:
            self.empty_hint = hint
            self.refresh()

    # -- rows --------------------------------------------------------------------------------

    @property
    def row_count(self) -> int:
        if self.paused_end is None:
            return len(self.view)
        return self.view.count_before(self.paused_end)

    @property
    def cursor_row(self) -> int:
        return self.cursor.row

    @property
    def cursor_seq(self) -> int | None:
        return self.cursor.seq(self.view, self.row_count)

    @property
    def cursor_last_seq(self) -> int | None:
        """The last message the cursor's row shows: a collapsed storm's last repeat, else
        the row's own (where a search down from the row starts)."""
        seq = self.cursor_seq
        badge = self.decorations.badge_of(seq) if seq is not None else None
        return badge.last if badge is not None and badge.head and not badge.expanded else seq

    @property
    def selection_anchor(self) -> int | None:
        return self.cursor.anchor

    def selected_rows(self) -> range:
        return self.cursor.selected_rows(self.view, self.row_count)

    def selected_seqs(self, at_most: int) -> list[int]:
        return self.cursor.selected_seqs(self.view, self.row_count, at_most)

    @property
    def new_while_paused(self) -> int:
        """Rows that arrived since the pause (shown on resume)."""
        if self.paused_end is None:
            return 0
        return len(self.view) - self.row_count

    @property
    def _body_height(self) -> int:
        return max(self.scrollable_content_region.height - 1, 1)

    @contextmanager
    def keeping_position(self, *, cursor_line: bool = False) -> Iterator[None]:
        """Wrap a store/view update: the rows under the cursor and at the top stay put. With
        ``cursor_line`` (rows come and go above and below it: the rules changed) the cursor's
        record stays on its line of the screen instead, or the nearest shown in time."""
        top = int(self.scroll_y)
        top_seq = self.view.seq_at(top) if 0 <= top < self.row_count else None
        cursor_seq = self.cursor_seq
        shown = self._shown_seqs(top)
        line = self.cursor.row - top if cursor_line and cursor_seq is not None else None
        yield
        self._after_update(top_seq, cursor_seq, shown, line)

    def _after_update(
        self, top_seq: int | None, cursor_seq: int | None, shown: tuple | None = None, line: int | None = None
    ) -> None:
        rows = self.row_count
        cursor = self.cursor
        top: int | None
        if self.following and self.paused_end is None:
            cursor.row = max(rows - 1, 0)
            top = self._end_top()
        else:
            if cursor_seq is not None:
                place = place_of(cursor_seq, self.view, rows, self.store, nearest=line is not None)
                cursor.row = min(place, max(rows - 1, 0))
            else:
                cursor.row = min(cursor.row, max(rows - 1, 0))
            top = self.view.row_of(top_seq) if top_seq is not None else None
            if line is not None:
                top = max(cursor.row - line, 0)
        if shown is not None and top is not None:
            now = self._shown_seqs(top)
            changed = _badges_changed(shown, now, badges=self.decorations.badges is not None)
            if changed is not None:
                # The same rows on screen (older ones were filtered in, or new ones arrived
                # below while scrolled up): only the scroll offset and, a few times a second,
                # the scrollbar move; only rows whose storm count changed are redrawn.
                self.set_height(rows + 1, quiet=True)
                self.set_reactive(ScrollView.scroll_y, float(top))
                self.set_reactive(ScrollView.scroll_target_y, float(top))
                for line in changed:
                    self.refresh(Region(0, self.gutter.top + 1 + line, self.outer_size.width, 1))
                return
        self.set_height(rows + 1)
        if top is not None:
            self.set_scroll(None, top)
        self.refresh()
        self.post_message(self.StateChanged())

    def _shown_seqs(self, top: int) -> tuple[object, ...]:
        """The cursor's seq and those of the rows on screen with ``top`` as the first row."""
        seq_at = self.view.seq_at
        end = min(top + self._body_height, self.row_count)
        seqs = [seq_at(row) for row in range(max(top, 0), end)]
        badges = self.decorations.badges
        if badges is not None:  # a storm's count changes its row
            return (self.cursor_seq, *seqs, *map(badges, seqs))
        return (self.cursor_seq, *seqs)

    def reset(self) -> None:
        """After a clear or a new filter: back to the tail."""
        self.lines.forget()
        self.cursor.row = 0
        self.following = True
        self._after_update(None, None)

    # -- following and pause -------------------------------------------------------------------

    def follow(self) -> None:
        self.following = True
        if self.paused_end is not None:
            self.paused_end = None
        self._after_update(None, None)

    def set_paused(self, paused: bool) -> None:
        if paused and self.paused_end is None:
            self.paused_end = self.store.end_seq
        elif not paused and self.paused_end is not None:
            with self.keeping_position():
                self.paused_end = None
        self.post_message(self.StateChanged())

    def _stop_following(self) -> None:
        if self.following:
            self.following = False
            self.post_message(self.StateChanged())

    # -- the cursor and scrolling -----------------------------------------------------------------

    def move_cursor(self, row: int, *, extend: bool = False) -> None:
        """Move the cursor to ``row``; ``extend`` selects the rows from where it was."""
        rows = self.row_count
        if row < 0 and self.cursor.row == 0:
            self.post_message(self.TopReached())  # older rows may be asked for
        if rows == 0:
            return
        self.cursor.move(row, self.view, rows, extend=extend)
        row = self.cursor.row
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

    def _end_top(self) -> int:
        """The top row when the last row is at the bottom of the screen."""
        return max(self.row_count + 1 - self.scrollable_content_region.height, 0)

    def watch_scroll_y(self, old: float, new: float) -> None:
        super().watch_scroll_y(old, new)
        if new < old and new < self.max_scroll_y:
            self._stop_following()

    def action_cursor_up(self) -> None:
        self.move_cursor(self.cursor.row - 1)

    def action_cursor_down(self) -> None:
        self.move_cursor(self.cursor.row + 1)

    def action_select_up(self) -> None:
        self.move_cursor(self.cursor.row - 1, extend=True)

    def action_select_down(self) -> None:
        self.move_cursor(self.cursor.row + 1, extend=True)

    def action_clear_selection(self) -> None:
        if self.cursor.anchor is None:
            raise SkipAction()  # Esc goes on to the app (it stops a long filtering)
        self.cursor.anchor = None
        self.refresh()

    def action_page_up(self) -> None:
        self.move_cursor(self.cursor.row - self._body_height)

    def action_page_down(self) -> None:
        self.move_cursor(self.cursor.row + self._body_height)

    def action_first_row(self) -> None:
        self.move_cursor(-1 if self.cursor.row == 0 else 0)

    def action_follow(self) -> None:
        self.follow()

    def action_activate(self) -> None:
        seq = self.cursor_seq
        if seq is not None:
            self.post_message(self.RowActivated(seq))

    async def _on_click(self, event: events.Click) -> None:
        row = int(self.scroll_y) + event.y - 1
        if event.y < 1 or row >= self.row_count:
            return
        self.move_cursor(row, extend=event.shift)
        if event.chain >= 2:
            self.action_activate()

    def on_mount(self) -> None:
        self._after_update(None, None)

    def on_resize(self, event: events.Resize) -> None:
        self.set_height(self.row_count + 1)
        if self.following and self.paused_end is None:
            self.set_scroll(None, self._end_top())

    # -- the columns ----------------------------------------------------------------------------

    def set_time_format(self, fmt: TimeFormat, utc: bool) -> None:
        """What the Time column shows, local time or UTC."""
        self.painter.time_format, self.painter.utc = fmt, utc
        self.lines.forget()
        self.refresh()

    def set_column_shown(self, key: str, shown: bool) -> None:
        self.painter.set_column_shown(key, shown)
        self.lines.forget()
        self.refresh()

    # -- drawing ----------------------------------------------------------------------------------

    def restyle(self) -> None:
        """The rows look different (the decorations changed): every row is drawn again."""
        self.lines.restyled()
        self.refresh()

    def notify_style_update(self) -> None:
        super().notify_style_update()
        self._styles_key = None

    def render_lines(self, crop: Region) -> list[Strip]:
        # What every row needs, worked out once a frame: the component styles (looked up again
        # only when the focus, the theme or the CSS changed: the lookups cost more than
        # drawing a row) and the columns.
        styles_key = (self.has_focus, self.app.theme)
        if styles_key != self._styles_key:
            self._styles_key = styles_key
            names = self.COMPONENT_CLASSES
            self.lines.set_styles(
                {name: self.get_component_rich_style(name, partial=True) for name in names}, self.rich_style
            )
        self._width = self.scrollable_content_region.width
        if self.painter.layout(self._width, gutter=self.decorations.gutter is not None):
            self.lines.forget()
        if self.styles.padding != _NO_SPACING or self.styles.border.spacing != _NO_SPACING:
            return super().render_lines(crop)
        # No border or padding to draw: the rows go straight to the screen (with the app's
        # line filters), which saves Textual's per-line styling work on every frame; at
        # thousands of messages a second every visible row is new in every frame. Textual
        # redraws every widget under a changed region (the scrollbar, a notification): the
        # same rows in the same styles give the same strips as last time.
        filters = self.get_line_filters()
        background = self.background_colors[1]
        full_width = self.size.width  # the scrollbar gutter too, when no scrollbar covers it
        frame_key = (
            crop,
            full_width,
            self._shown_seqs(int(self.scroll_y)),
            self.cursor.anchor,
            self.lines.generation,
            styles_key,
            self.painter.layout_key,
            background,
            self.empty_hint if not self.row_count else "",
            *map(id, filters),
        )
        return self.lines.frame(frame_key, crop, full_width, filters, background, self.render_line)

    def render_line(self, y: int) -> Strip:
        top, rows, count = int(self.scroll_y), self.view, self.row_count
        return self.lines.line(
            y, top=top, rows=rows, count=count, cursor=self.cursor, width=self._width, hint=self.empty_hint
        )


def _badges_changed(before: tuple[object, ...], after: tuple[object, ...], *, badges: bool) -> list[int] | None:
    """The rows on screen (0: the first, under the header) whose storm badge changed
    between two ``_shown_seqs``, when the cursor and the rows are the same; else None."""
    if before == after:
        return []
    if not badges or len(before) != len(after):
        return None
    rows = len(before) // 2
    if before[: rows + 1] != after[: rows + 1]:
        return None
    return [line for line in range(rows) if before[rows + 1 + line] != after[rows + 1 + line]]


__all__ = ["Decoration", "LogTable", "Spans", "TableRows"]
