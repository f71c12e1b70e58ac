"""The table's keys that need more than the table: clear, the columns shown, a row's details."""

from __future__ import annotations

from collections.abc import Callable

from ...model.overview.node_stats import NodeStats
from ...model.store.log_store import LogStore
from ...model.store.record import LogRecord
from ...model.view.log_view import LogView
from ...model.view.marks import Marks
from ..widgets.log_table import LogTable
from ..widgets.table_columns import COLUMNS
from .host import Host
from .overview import OverviewController


class TableController:
    """Clear, columns and details."""

    def __init__(
        self,
        host: Host,
        store: LogStore,
        view: LogView,
        table: LogTable,
        marks: Marks,
        node_stats: NodeStats,
        overview: OverviewController,
        *,
        source_notes: dict[str, list[str]],
        utc: bool,
        update_status: Callable[[], None],
    ) -> None:
        self._host = host
        self._store = store
        self._view = view
        self._table = table
        self._marks = marks
        self._node_stats = node_stats
        self._overview = overview
        #: How loaded files were read, by source: the detail view says it.
        self._source_notes = source_notes
        self._utc = utc
        self._update_status = update_status

    def clear(self) -> None:
        """Drop every message."""
        self._marks.clear()
        self._store.clear()
        self._node_stats.clear()
        self._view.rebuild()
        self._overview.restart()
        self._table.reset()
        self._update_status()

    # -- columns ----------------------------------------------------------------------------------

    def ask_columns(self) -> None:
        table = self._table

        def apply(shown: frozenset[str] | None) -> None:
            if shown is not None:
                for column in COLUMNS:
                    table.set_column_shown(column.key, column.key in shown)

        from ..screens.columns_dialog import ColumnsScreen  # loaded when first opened

        self._host.push_screen(ColumnsScreen(table.shown_columns), apply)

    def toggle_column(self, key: str) -> None:
        self._table.set_column_shown(key, key not in self._table.shown_columns)

    # -- a row's details --------------------------------------------------------------------------

    def open_detail(self, seq: int) -> None:
        if seq not in self._store:
            return
        from ..screens.detail import DetailScreen  # loaded when first opened, with the file formats

        self._host.push_screen(
            DetailScreen(self._store.get(seq), utc=self._utc, step=self._step_record, source_notes=self._source_notes)
        )

    def _step_record(self, seq: int, delta: int) -> LogRecord | None:
        """The record ``delta`` rows away from ``seq`` in the table, moving the cursor too."""
        table = self._table
        row = table.view.row_of(seq) + delta
        if not 0 <= row < table.row_count:
            return None
        table.move_cursor(row)
        return self._store.get(table.view.seq_at(row))
