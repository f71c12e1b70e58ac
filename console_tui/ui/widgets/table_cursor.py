"""The log table's cursor and the rows selected with it: which row the cursor is on, where a
selection began, which rows (and seqs) are selected, and the row of a record (or the one
nearest it in time) to put the cursor on. A plain object the table owns: the rows and how many
are shown (fewer while paused) are given to each call; scrolling is the table's.
"""

from __future__ import annotations

from ...model.store.log_store import LogStore
from .table_rows import TableRows


class TableCursor:
    """The cursor's row, and the seq where a selection began (shift+arrows), or None: the
    cursor's row alone is selected."""

    __slots__ = ("anchor", "row")

    def __init__(self) -> None:
        self.row = 0
        self.anchor: int | None = None

    def seq(self, rows: TableRows, count: int) -> int | None:
        """The seq of the cursor's row, or None (no rows)."""
        return rows.seq_at(self.row) if 0 <= self.row < count else None

    def move(self, row: int, rows: TableRows, count: int, *, extend: bool = False) -> None:
        """To ``row`` of ``count`` (clamped); ``extend`` selects the rows from where it was."""
        if not extend:
            self.anchor = None
        elif self.anchor is None:
            self.anchor = self.seq(rows, count)
        self.row = min(max(row, 0), count - 1)

    def selected_rows(self, rows: TableRows, count: int) -> range:
        """The selected rows (the cursor's alone when nothing else is selected)."""
        if count == 0:
            return range(0)
        anchor = self.row if self.anchor is None else rows.row_of(self.anchor)
        anchor = min(anchor, count - 1)
        return range(min(anchor, self.row), max(anchor, self.row) + 1)

    def selected_seqs(self, rows: TableRows, count: int, at_most: int) -> list[int]:
        """The seqs of the selected rows, the first ``at_most`` of them."""
        return [rows.seq_at(row) for row in self.selected_rows(rows, count)[:at_most]]


def place_of(seq: int, rows: TableRows, count: int, store: LogStore, *, nearest: bool) -> int:
    """The row of ``seq``; when no row shows it, the next row, or (``nearest``) the row of the
    ``count`` shown nearest it in time."""
    if not nearest:
        return rows.row_of(seq)
    shown = rows.row_shown(seq)
    if shown is not None:
        return shown
    after = rows.row_of(seq)
    if after == 0 or after >= count or seq not in store:
        return after
    stamp = store.stamp_of(seq)
    before_gap = stamp - store.stamp_of(rows.seq_at(after - 1))
    after_gap = store.stamp_of(rows.seq_at(after)) - stamp
    return after - 1 if before_gap <= after_gap else after
