"""The log table's columns as laid out: which are shown, how wide the node column is, what the
Time column shows, and the gutter of marks; laid out again only when one of them or the width
changed (the columns themselves, and how they share the width: ``table_columns.py``).

A part of ``LogTable`` (it mixes this in).
"""

from __future__ import annotations

from collections.abc import Callable

from rich.cells import cell_len
from textual.scroll_view import ScrollView

from ...model.store.log_store import LogStore
from ...model.time_column import TimeFormat, format_info
from .log_table_cells import GUTTER
from .table_columns import PlacedColumn, layout_columns


class TableLayout(ScrollView):
    """The columns' places for a width (``LogTable`` mixes this in)."""

    # What it reads of the table (``LogTable`` sets them).
    store: LogStore
    utc: bool
    time_format: TimeFormat
    shown_columns: frozenset[str]
    gutter_of: Callable[[int], str] | None
    restyle: Callable[[], None]
    _forget_drawn_rows: Callable[[], None]
    # Its own (``LogTable.__init__`` sets them first).
    _layout_key: tuple
    _nodes_measured: int
    _widest_node: int
    _placed: tuple[PlacedColumn, ...]

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
        gutter = GUTTER if self.gutter_of is not None else 0
        # A fleet's robots: as wide as the widest name, 5 to 16 cells.
        robot_width = max(min(max(map(cell_len, self.store.robots), default=5), 16), 5)
        # The row number's digits, however long the history (8 for 20,000,000).
        seq_width = max(7, len(str(self.store.end_seq)))
        key = (width, self.shown_columns, node_width, gutter, self.time_format, self.utc, robot_width, seq_width)
        if key != self._layout_key:
            self._layout_key = key
            widths = {"time": format_info(self.time_format).width, "robot": robot_width, "seq": seq_width}
            self._placed = layout_columns(width - gutter, self.shown_columns, node_width, widths)
            self._forget_drawn_rows()
        return self._placed

    @property
    def placed_columns(self) -> tuple[PlacedColumn, ...]:
        return self._placed
