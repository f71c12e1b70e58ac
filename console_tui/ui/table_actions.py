"""The app's table: pause and follow, clear, the columns shown, a row's details.

A part of ``ConsoleApp`` (it mixes this in): the table's keys that need more than the table
(the store, the overview, the screens), and what its messages ask of the app.
"""

from __future__ import annotations

from dataclasses import replace

from ..model.marks import Marks
from ..model.node_stats import NodeStats
from ..model.record import LogRecord
from .app_part import AppPart
from .controllers.files import FilesController
from .controllers.overview import OverviewController
from .screens.columns_dialog import ColumnsScreen
from .screens.detail import DetailScreen
from .widgets.log_table import LogTable
from .widgets.table_columns import COLUMNS


class TableActions(AppPart):
    """Pause, follow, clear, columns and details."""

    overview: OverviewController
    files: FilesController

    # What it uses of the app (``ConsoleApp`` sets them).
    marks: Marks
    node_stats: NodeStats
    #: Whether the footer names the pause key Resume.
    _shown_paused = False

    def action_toggle_pause(self) -> None:
        table = self.table
        table.set_paused(table.paused_end is None)

    def action_follow(self) -> None:
        self.table.follow()

    def on_log_table_state_changed(self, _message: LogTable.StateChanged) -> None:
        self.update_status()
        self.overview.show(force=True)
        paused = self.table.paused_end is not None
        if paused != self._shown_paused:
            self._shown_paused = paused
            self.name_pause_key(paused)

    def name_pause_key(self, paused: bool) -> None:
        """The footer names what the pause key does now: Pause, or Resume while paused. (The
        app's own bindings are changed in place; a keymap applies over them as before.)"""
        words = "Resume" if paused else "Pause"
        table = self._bindings.key_to_bindings
        for key, bindings in table.items():
            table[key] = [replace(b, description=words) if b.id == "console.pause" else b for b in bindings]
        self.refresh_bindings()

    def action_clear(self) -> None:
        self.marks.clear()
        self.store.clear()
        self.node_stats.clear()
        self.view.rebuild()
        self.overview.restart()
        self.table.reset()
        self.update_status()

    # -- columns ----------------------------------------------------------------------------------

    def action_columns(self) -> None:
        def apply(shown: frozenset[str] | None) -> None:
            if shown is not None:
                table = self.table
                for column in COLUMNS:
                    table.set_column_shown(column.key, column.key in shown)

        self.push_screen(ColumnsScreen(self.table.shown_columns), apply)

    def action_toggle_column(self, key: str) -> None:
        self.table.set_column_shown(key, key not in self.table.shown_columns)

    # -- a row's details --------------------------------------------------------------------------

    def action_details(self) -> None:
        self.table.action_activate()

    def on_log_table_row_activated(self, message: LogTable.RowActivated) -> None:
        self.open_detail(message.seq)

    def open_detail(self, seq: int) -> None:
        if seq not in self.store:
            return
        self.push_screen(
            DetailScreen(
                self.store.get(seq), utc=self.utc, step=self._step_record, source_notes=self.files.source_notes
            )
        )

    def _step_record(self, seq: int, delta: int) -> LogRecord | None:
        """The record ``delta`` rows away from ``seq`` in the table, moving the cursor too."""
        table = self.table
        row = table.view.row_of(seq) + delta
        if not 0 <= row < table.row_count:
            return None
        table.move_cursor(row)
        return self.store.get(table.view.seq_at(row))
