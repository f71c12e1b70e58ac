"""The log table: a line-API view over the store that renders only the visible rows.

Rows are addressed by store seq, which never changes, so rendered rows are cached by seq
and the position survives records arriving and old ones being evicted. Line 0 is a fixed
header; line ``y`` shows row ``scroll_y + y - 1``.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from functools import lru_cache
from typing import Protocol

from rich.cells import cell_len, set_cell_size
from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.actions import SkipAction
from textual.binding import Binding
from textual.cache import LRUCache
from textual.geometry import Region, Size, Spacing
from textual.message import Message
from textual.scroll_view import ScrollView
from textual.strip import Strip

from ...model.levels import severity_level, severity_name
from ...model.record import LogRecord
from ...model.store import LogStore
from ...model.storms import StormBadge
from ...model.text import one_line, shorten_name
from ...model.time_column import TimeFormat, column_title, format_info, time_cell
from ...model.timefmt import clock_text, duration_text
from ..severity_styles import severity_classes, severity_css
from .table_columns import BY_KEY, COLUMNS, PlacedColumn, layout_columns

#: How a row is marked by the rules: None (plain), "highlight" or "dim".
Decoration = str | None
#: Where a search matches in a message as shown: (start, end) character spans.
Spans = list[tuple[int, int]]


class TableRows(Protocol):
    """What the table reads its rows from: a ``LogView``, or ``StormRows`` over one."""

    def __len__(self) -> int: ...

    def seq_at(self, row: int) -> int: ...

    def row_of(self, seq: int) -> int: ...

    def count_before(self, seq: int) -> int: ...

    def row_shown(self, seq: int) -> int | None: ...


_MESSAGE_LIMIT = 2000
_NO_SPACING = Spacing(0, 0, 0, 0)
#: How often the scrollbar follows changes that leave the rows on screen as they were (s).
_QUIET_SCROLLBAR_PERIOD = 0.1


class LogTable(ScrollView, can_focus=True):
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

    class RowActivated(Message):
        """Enter or a double click on a row."""

        def __init__(self, seq: int) -> None:
            super().__init__()
            self.seq = seq

    class StateChanged(Message):
        """Following, pause or cursor changed (for the status bar)."""

        def can_replace(self, message: Message) -> bool:
            return isinstance(message, LogTable.StateChanged)  # it says nothing but "look again"

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
    def keeping_position(self) -> Iterator[None]:
        """Wrap a store/view update: the rows under the cursor and at the top stay put."""
        top = int(self.scroll_y)
        top_seq = self.view.seq_at(top) if 0 <= top < self.row_count else None
        cursor_seq = self.cursor_seq
        shown = self._shown_seqs(top)
        yield
        self._after_update(top_seq, cursor_seq, shown)

    def _after_update(self, top_seq: int | None, cursor_seq: int | None, shown: tuple | None = None) -> None:
        rows = self.row_count
        top: int | None
        if self.following and self.paused_end is None:
            self.cursor_row = max(rows - 1, 0)
            top = self._end_top()
        else:
            if cursor_seq is not None:
                self.cursor_row = min(self.view.row_of(cursor_seq), max(rows - 1, 0))
            else:
                self.cursor_row = min(self.cursor_row, max(rows - 1, 0))
            top = self.view.row_of(top_seq) if top_seq is not None else None
        if shown is not None and top is not None and self._shown_seqs(top) == shown:
            # The same rows on screen (older ones were filtered in, or new ones arrived below
            # while scrolled up): only the scroll offset and, a few times a second, the
            # scrollbar move; the table is not redrawn.
            self._update_virtual_size(quiet=True)
            self.set_reactive(ScrollView.scroll_y, float(top))
            self.set_reactive(ScrollView.scroll_target_y, float(top))
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

    def _forget_drawn_rows(self) -> None:
        self._cache.clear()
        self._frame = None

    def restyle(self) -> None:
        """Decorations changed (rules): drop cached rows and redraw."""
        self.style_generation += 1
        self._forget_drawn_rows()
        self.refresh()

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

    # -- cursor and scrolling ----------------------------------------------------------------

    def move_cursor(self, row: int, *, extend: bool = False) -> None:
        """Move the cursor to ``row``; ``extend`` selects the rows from where it was."""
        rows = self.row_count
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

    def _scroll_to_row_end(self) -> None:
        self.set_scroll(None, self._end_top())

    def watch_scroll_y(self, old: float, new: float) -> None:
        super().watch_scroll_y(old, new)
        if new < old and new < self.max_scroll_y:
            self._stop_following()

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

    def action_page_up(self) -> None:
        self.move_cursor(self.cursor_row - self._body_height)

    def action_page_down(self) -> None:
        self.move_cursor(self.cursor_row + self._body_height)

    def action_first_row(self) -> None:
        self.move_cursor(0)

    def action_follow(self) -> None:
        self.follow()

    def action_activate(self) -> None:
        seq = self.cursor_seq
        if seq is not None:
            self.post_message(self.RowActivated(seq))

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

    def on_mount(self) -> None:
        self._after_update(None, None)

    def on_resize(self, event: events.Resize) -> None:
        self._update_virtual_size()
        if self.following and self.paused_end is None:
            self._scroll_to_row_end()

    # -- columns --------------------------------------------------------------------------------

    def set_time_format(self, fmt: TimeFormat, utc: bool) -> None:
        """What the Time column shows, local time or UTC."""
        self.time_format, self.utc = fmt, utc
        self._forget_drawn_rows()
        self.refresh()

    def set_gutter(self, gutter_of: Callable[[int], str] | None) -> None:
        """Show a gutter of marks left of the rows (or none)."""
        if gutter_of is not self.gutter_of:
            self.gutter_of = gutter_of
            self.restyle()

    def set_column_shown(self, key: str, shown: bool) -> None:
        columns = set(self.shown_columns)
        (columns.add if shown else columns.discard)(key)
        if "message" not in columns:
            columns.add("message")
        self.shown_columns = frozenset(columns)
        self._forget_drawn_rows()
        self.refresh()

    def _layout(self, width: int) -> tuple[PlacedColumn, ...]:
        nodes = self.store.nodes
        if len(nodes) != self._nodes_measured:
            self._nodes_measured = len(nodes)
            self._widest_node = max((cell_len(name) for name in nodes), default=8)
        # Wide enough for most names whole (20 of 80 columns, 24 of 100, 32 of 160); longer
        # ones are shortened from the front, keeping the end that tells them apart (shorten_name).
        node_width = max(min(self._widest_node, max(24, width // 5), max((width + 3) // 4, 12)), 6)
        gutter = _GUTTER if self.gutter_of is not None else 0
        key = (width, self.shown_columns, node_width, gutter, self.time_format, self.utc)
        if key != self._layout_key:
            self._layout_key = key
            widths = {"time": format_info(self.time_format).width}
            self._placed = layout_columns(width - gutter, self.shown_columns, node_width, widths)
            self._forget_drawn_rows()
        return self._placed

    @property
    def placed_columns(self) -> tuple[PlacedColumn, ...]:
        return self._placed

    # -- rendering --------------------------------------------------------------------------------

    def notify_style_update(self) -> None:
        super().notify_style_update()
        self._styles_key = None

    def _look_up_styles(self) -> None:
        """Component styles, looked up again only when the focus, the theme or the CSS changed
        (the lookups cost more than drawing a row); rows drawn in old styles are dropped."""
        key = (self.has_focus, self.app.theme)
        if key != self._styles_key:
            self._styles_key = key
            self._styles = {name: self.get_component_rich_style(name, partial=True) for name in self.COMPONENT_CLASSES}
            self._base = self.rich_style
            self._forget_drawn_rows()

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
                return Strip([Segment(_fit("  " + one_line(self.empty_hint, 400), width), style)], width)
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

    def _header(self, placed: tuple[PlacedColumn, ...], width: int, base: Style) -> Strip:
        style = base + self._styles.get("log-table--header", Style())
        segments: list[Segment] = []
        if self.gutter_of is not None:
            segments.append(Segment(" " * _GUTTER, style))
        for place in placed:
            title = column_title(self.time_format, self.utc) if place.column.key == "time" else place.column.title
            segments.append(Segment(_fit(title, place.width, place.column.align) + " ", style))
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
        segments: list[Segment] = []
        if gutter is not None:
            segments.append(Segment(_fit(gutter, 1), row_style + styles.get("log-table--gutter", Style())))
            segments.append(Segment(" ", row_style))
        for place in placed:
            key = place.column.key
            if key == "message" and badge is not None:
                mark = self._badge_text(badge, place.width)
                segments.append(Segment(mark, row_style + styles.get("log-table--storm", Style())))
                room = place.width - len(mark)
                text = self._cell_text(record, key, room)
                segments.extend(self._message_segments(record.seq, text, _fit(text, room), row_style))
                segments.append(Segment(" ", row_style))
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
            elif key in ("seq", "time", "file", "function", "line", "source") and name != "debug" and not is_cursor:
                style = row_style + muted
            fitted = _fit(text, place.width, place.column.align)
            if key == "message":
                segments.extend(self._message_segments(record.seq, text, fitted, style))
            else:
                segments.append(Segment(fitted, style))
            segments.append(Segment(" ", row_style))
        return Strip(segments).adjust_cell_length(width, row_style).simplify()

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
        raise KeyError(key)


@lru_cache(maxsize=4096)
def _node_text(node: str, width: int) -> str:
    return shorten_name(one_line(node, 200), width)


def _marked(fitted: str, spans: Spans, length: int, style: Style, marked: Style) -> list[Segment]:
    """``fitted`` (a cell's text cut or padded by ``_fit``) with ``spans`` of the text before
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


#: Cells of the gutter (a mark, and a space).
_GUTTER = 2


def _fit(text: str, width: int, align: str = "left") -> str:
    """Exactly ``width`` cells: padded, or cut with an ellipsis."""
    length = len(text) if text.isascii() else cell_len(text)
    if length > width:
        return set_cell_size(text, max(width - 1, 0)) + ("…" if width else "")
    if align == "right":
        return " " * (width - length) + text
    return text + " " * (width - length)


__all__ = ["BY_KEY", "LogTable"]
