"""The log table: a line-API view over the store that renders only the visible rows.

Rows are addressed by store seq, which never changes, so rendered rows are cached by seq
and the position survives records arriving and old ones being evicted. Line 0 is a fixed
header; line ``y`` shows row ``scroll_y + y - 1``.

This file holds the widget, which rows it shows and where (following the tail, the pause,
keeping its place as records come and go); its parts, mixed in: the cursor and the selection
(``log_table_cursor.py``), drawing a frame with its caches (``log_table_frame.py``), the
columns as laid out (``log_table_layout.py``) and one row's cells (``log_table_cells.py``).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass

from rich.style import Style
from textual import events
from textual.binding import Binding
from textual.cache import LRUCache
from textual.geometry import Region, Size
from textual.message import Message
from textual.scroll_view import ScrollView
from textual.scrollbar import ScrollBar
from textual.strip import Strip

from ...model.store import LogStore
from ...model.storms import StormBadge
from ...model.time_column import TimeFormat
from ..severity_styles import severity_classes, severity_css
from .log_table_cells import Decoration, Spans
from .log_table_cursor import TableCursor
from .log_table_frame import TableFrame
from .table_columns import COLUMNS, PlacedColumn
from .table_rows import TableRows
from .table_scrollbar import TableScrollBar

#: How often the scrollbar follows changes that leave the rows on screen as they were (s).
_QUIET_SCROLLBAR_PERIOD = 0.1


class LogTable(TableCursor, TableFrame, can_focus=True):
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

    DEFAULT_CSS = (
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

    COMPONENT_CLASSES = {
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

    def __init__(self, store: LogStore, view: TableRows, *, utc: bool = False, id: str | None = None) -> None:
        super().__init__(id=id)
        self.store = store
        self.view = view
        self.utc = utc
        self.following = True
        #: While paused, rows for seqs at or past this are not shown.
        self.paused_end: int | None = None
        self.cursor_row = 0
        #: The seq where a selection of rows began (shift+arrows), or None: the cursor's row only.
        self.selection_anchor: int | None = None
        self.shown_columns: frozenset[str] = frozenset(c.key for c in COLUMNS if c.shown_by_default)
        #: Rules hook: seq -> decoration; bump ``style_generation`` when its answers change.
        self.decoration_of: Callable[[int], Decoration] | None = None
        #: Storms hook: seq -> how its row is marked as a storm (``×N until ...``), or None.
        self.badge_of: Callable[[int], StormBadge | None] | None = None
        #: Marks and search hook: seq -> one character for the gutter left of the row ("" for
        #: none), or None: no gutter. Bump ``style_generation`` when its answers change.
        self.gutter_of: Callable[[int], str] | None = None
        #: Search hook: (seq, message as shown) -> the spans to mark in it.
        self.match_spans: Callable[[int, str], Spans] | None = None
        #: What the Time column shows (``t``), in local time or UTC.
        self.time_format = TimeFormat.CLOCK
        self.style_generation = 0
        #: Said in the empty table (``show_hint``): what the console waits for, or that rules
        #: hide every message.
        self.empty_hint = ""
        # Rows drawn, for scrolling back over them. Kept to a few screens: each cached row is a
        # dozen objects for the cycle collector to visit (benchmarks/screen.py: 512 rows cost
        # about a fifth more per full collection than 192).
        self._cache: LRUCache[tuple, Strip] = LRUCache(192)
        self._layout_key: tuple = ()
        self._nodes_measured = 0
        self.robot_styles: dict[str, Style] = {}
        self._widest_node = 8
        self._placed: tuple[PlacedColumn, ...] = ()
        self._styles: dict[str, Style] = {}
        self._base = Style()
        self._styles_key: tuple | None = None
        self._width = 0
        self._scrollbar_sync_due = False
        #: The last strips ``render_lines`` returned, and what they were drawn from.
        self._frame: tuple[tuple, list[Strip]] | None = None

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
    def cursor_seq(self) -> int | None:
        if 0 <= self.cursor_row < self.row_count:
            return self.view.seq_at(self.cursor_row)
        return None

    @property
    def cursor_last_seq(self) -> int | None:
        """The last message the cursor's row shows: a collapsed storm's last repeat, else
        the row's own (where a search down from the row starts)."""
        seq = self.cursor_seq
        badge = self.badge_of(seq) if seq is not None and self.badge_of is not None else None
        return badge.last if badge is not None and badge.head and not badge.expanded else seq

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
        line = self.cursor_row - top if cursor_line and cursor_seq is not None else None
        yield
        self._after_update(top_seq, cursor_seq, shown, line)

    def _after_update(
        self, top_seq: int | None, cursor_seq: int | None, shown: tuple | None = None, line: int | None = None
    ) -> None:
        rows = self.row_count
        top: int | None
        if self.following and self.paused_end is None:
            self.cursor_row = max(rows - 1, 0)
            top = self._end_top()
        else:
            if cursor_seq is not None:
                self.cursor_row = min(self._place_of(cursor_seq, line is not None), max(rows - 1, 0))
            else:
                self.cursor_row = min(self.cursor_row, max(rows - 1, 0))
            top = self.view.row_of(top_seq) if top_seq is not None else None
            if line is not None:
                top = max(self.cursor_row - line, 0)
        if shown is not None and top is not None:
            now = self._shown_seqs(top)
            changed = _badges_changed(shown, now, badges=self.badge_of is not None)
            if changed is not None:
                # The same rows on screen (older ones were filtered in, or new ones arrived
                # below while scrolled up): only the scroll offset and, a few times a second,
                # the scrollbar move; only rows whose storm count changed are redrawn.
                self._update_virtual_size(quiet=True)
                self.set_reactive(ScrollView.scroll_y, float(top))
                self.set_reactive(ScrollView.scroll_target_y, float(top))
                for line in changed:
                    self.refresh(Region(0, self.gutter.top + 1 + line, self.outer_size.width, 1))
                return
        self._update_virtual_size()
        if top is not None:
            self.set_scroll(None, top)
        self.refresh()
        self.post_message(self.StateChanged())

    def _shown_seqs(self, top: int) -> tuple[object, ...]:
        """The cursor's seq and those of the rows on screen with ``top`` as the first row."""
        seq_at = self.view.seq_at
        end = min(top + self._body_height, self.row_count)
        seqs = [seq_at(row) for row in range(max(top, 0), end)]
        if self.badge_of is not None:  # a storm's count changes its row
            return (self.cursor_seq, *seqs, *map(self.badge_of, seqs))
        return (self.cursor_seq, *seqs)

    def reset(self) -> None:
        """After a clear or a new filter: back to the tail."""
        self._forget_drawn_rows()
        self.cursor_row = 0
        self.following = True
        self._after_update(None, None)

    def _update_virtual_size(self, *, quiet: bool = False) -> None:
        size = Size(self.scrollable_content_region.width, self.row_count + 1)
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
        redraws every widget under it, this table included)."""
        self._scrollbar_sync_due = False
        self._scroll_update(self.virtual_size)
        if self.show_vertical_scrollbar:
            self.vertical_scrollbar.position = self.scroll_y

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

    # -- scrolling ------------------------------------------------------------------------------

    def _end_top(self) -> int:
        """The top row when the last row is at the bottom of the screen."""
        return max(self.row_count + 1 - self.scrollable_content_region.height, 0)

    def _scroll_to_row_end(self) -> None:
        self.set_scroll(None, self._end_top())

    def watch_scroll_y(self, old: float, new: float) -> None:
        super().watch_scroll_y(old, new)
        if new < old and new < self.max_scroll_y:
            self._stop_following()

    def action_follow(self) -> None:
        self.follow()

    def action_activate(self) -> None:
        seq = self.cursor_seq
        if seq is not None:
            self.post_message(self.RowActivated(seq))

    def on_mount(self) -> None:
        self._after_update(None, None)

    def on_resize(self, event: events.Resize) -> None:
        self._update_virtual_size()
        if self.following and self.paused_end is None:
            self._scroll_to_row_end()


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
