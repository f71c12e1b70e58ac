"""The table's commands that need more than the table: pause, clear, the columns shown (the
Robot column when records of two robots come), a row's details."""

from __future__ import annotations

from collections.abc import Callable
from typing import ClassVar

from ...model.store.record import LogRecord
from ..command_table import Command
from ..widgets.table_columns import COLUMNS
from .announcements import TakenIn
from .context import ConsoleContext


def _toggling_column(key: str) -> Callable[[TableController], None]:
    return lambda table: table.toggle_column(key)


class TableController:
    """Pause, clear, columns and details."""

    def __init__(
        self, context: ConsoleContext, *, source_notes: dict[str, list[str]], robot_column: bool = False
    ) -> None:
        c = context
        self._host, self._store, self._view, self._table, self._marks = c.host, c.store, c.view, c.table, c.marks
        self._utc, self._changed, self._announce = c.utc, c.changed, c.announce
        #: How loaded files were read, by source: the detail view says it.
        self._source_notes = source_notes
        #: The Robot column was shown (a fleet given, or records of two robots came; the
        #: person may hide it again).
        self._robot_column = robot_column
        context.announce.taken_in.subscribe(self._after_records)

    # -- pause and the tail -----------------------------------------------------------------------

    @property
    def paused(self) -> bool:
        return self._table.paused_end is not None

    def pause(self) -> None:
        self._table.set_paused(True)

    def resume(self) -> None:
        self._table.set_paused(False)

    def toggle_pause(self) -> None:
        self._table.set_paused(not self.paused)

    def follow(self) -> None:
        self._table.follow()

    def clear(self) -> None:
        """Drop every message."""
        self._marks.clear()
        self._store.clear()
        self._view.rebuild()
        self._announce.cleared()
        self._table.reset()
        self._changed()

    def _after_records(self, taken: TakenIn) -> None:
        table = self._table
        if not self._robot_column and len(self._store.robots) > 2:  # "" and two robots or more
            self._robot_column = True
            table.set_column_shown("robot", True)
        if taken.rewritten:
            table.decorations.changed()  # rows drawn before show other records now

    # -- columns ----------------------------------------------------------------------------------

    def ask_columns(self) -> None:
        table = self._table

        def apply(shown: frozenset[str] | None) -> None:
            if shown is not None:
                for column in COLUMNS:
                    table.set_column_shown(column.key, column.key in shown)

        from ..screens.columns_dialog import ColumnsScreen  # loaded when first opened

        self._host.push_screen(ColumnsScreen(table.painter.shown_columns), apply)

    def toggle_column(self, key: str) -> None:
        self._table.set_column_shown(key, key not in self._table.painter.shown_columns)

    # -- a row's details --------------------------------------------------------------------------

    def details(self) -> None:
        """The selected row's details (as Enter in the table)."""
        self._table.action_activate()

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

    COMMANDS: ClassVar[tuple[Command[TableController], ...]] = (
        Command("console.pause", pause, "space", "Pause", footer=10, applies=lambda t: not t.paused),
        # Space is Pause or Resume, whichever applies (the footer says which): one key, one id.
        Command(
            "console.resume",
            resume,
            "space",
            "Resume",
            footer=10,
            applies=lambda t: t.paused,
            keys_of="console.pause",
        ),
        Command(
            "console.toggle_pause",
            toggle_pause,
            keys_of="console.pause",
            title="Pause / resume",
            about="Stop the view; messages keep arriving",
        ),
        Command(
            "console.follow",
            follow,
            keys_of="table.follow",
            title="Follow tail",
            about="Jump to the newest message and follow it",
        ),
        Command("console.clear", clear, "c", "Clear", footer=20, about="Drop every message"),
        Command(
            "console.details",
            details,
            keys_of="table.details",
            title="Details",
            about="Every field of the selected message; y copies it",
            words="copy yank",
        ),
        Command(
            "console.columns",
            ask_columns,
            "C",
            "Columns",
            footer=90,
            about="Choose the table's columns",
        ),
        *(
            Command(
                f"console.column_{column.key}",
                _toggling_column(column.key),
                title=f"Toggle column: {column.title}",
                about=f"Show or hide the {column.title} column",
            )
            for column in COLUMNS
            if column.key != "message"
        ),
    )
