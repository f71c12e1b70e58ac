"""Jumps: next / previous error and warning, first / last message, marks, and opening the
code file a message names in the person's editor.

A jump walks the history from the selected row with the model's ``Seeker``: a few milliseconds
at a time on the event loop, so a jump a million rows away never freezes the screen.
"""

from __future__ import annotations

import subprocess
from collections.abc import Callable
from typing import ClassVar

from textual.app import SuspendNotSupported

from ...model.inert_text import one_line
from ...model.levels import Severity
from ...model.view.seek import Hits, Seeker, level_hits, view_shows
from ..code_file import editor_command, find_code_file, run_editor, run_folders
from ..command_table import NAVIGATION, Command
from ..slicing import pause_between_slices
from .context import ConsoleContext

#: A jump looks this long at once, then goes on in slices of the same length.
SEEK_BUDGET_S = 0.008
SEEK_PAUSE_S = 0.001


def _seeking(level: int, forward: bool) -> Callable[[JumpsController], None]:
    if forward:
        return lambda jumps: jumps.next_level(level)
    return lambda jumps: jumps.previous_level(level)


class JumpsController:
    """Jumps to errors, warnings and marks; the code file a message names, in the editor."""

    def __init__(self, context: ConsoleContext, *, opened_paths: list[str]) -> None:
        c = context
        self._host, self._store, self._view, self._table, self._marks = c.host, c.store, c.view, c.table, c.marks
        self._changed = c.changed
        #: Every file and folder opened: where a message's bare file name may resolve.
        self._opened_paths = opened_paths
        self._marks_changed = c.announce.marks_changed

    # -- levels -----------------------------------------------------------------------------------

    def next_level(self, level: int) -> None:
        self._seek(level_hits(level), forward=True, what=f"{Severity(level).name} or worse")

    def previous_level(self, level: int) -> None:
        self._seek(level_hits(level), forward=False, what=f"{Severity(level).name} or worse")

    def _seek(self, hits: Hits, *, forward: bool, what: str) -> None:
        table = self._table
        seq = table.cursor_last_seq if forward else table.cursor_seq
        if seq is None:
            return
        seeker = Seeker(self._view, hits, seq, forward=forward, limit=table.paused_end)
        if seeker.step(SEEK_BUDGET_S):
            self._sought(seeker, what)
        else:
            self._host.run_worker(
                self._seek_in_background(seeker, what), name="_seek_in_background", group="seek", exclusive=True
            )

    async def _seek_in_background(self, seeker: Seeker, what: str) -> None:
        while not seeker.step(SEEK_BUDGET_S):
            await pause_between_slices(SEEK_PAUSE_S)
        self._sought(seeker, what)

    def _sought(self, seeker: Seeker, what: str) -> None:
        if seeker.found is not None:
            self._table.jump_to_seq(seeker.found)
        else:
            where = "below" if seeker.forward else "above"
            self._host.notify(f"No {what} {where}{'' if not seeker.failed else ': ' + seeker.failed}", timeout=3)

    # -- the ends ---------------------------------------------------------------------------------

    def first_row(self) -> None:
        self._table.move_cursor(0)

    def last_row(self) -> None:
        self._table.follow()

    # -- marks ------------------------------------------------------------------------------------

    def toggle_mark(self) -> None:
        seq = self._table.cursor_seq
        if seq is None:
            return
        self._marks.trim(self._store.first_seq)
        self._marks.toggle(seq)
        self._marks_changed()
        self._changed()

    def to_mark(self, *, forward: bool) -> None:
        table, marks, view = self._table, self._marks, self._view
        seq = table.cursor_last_seq if forward else table.cursor_seq
        marks.trim(self._store.first_seq)
        if seq is None or not len(marks):
            self._host.notify("No marks: m marks the selected row.", timeout=3)
            return
        limit = table.paused_end
        found = marks.nearest(
            seq, forward=forward, shown=lambda s: view_shows(view, s) and (limit is None or s < limit)
        )
        if found is None:
            self._host.notify(f"No mark {'below' if forward else 'above'} that the rules show.", timeout=3)
        else:
            table.jump_to_seq(found)

    def list_marks(self) -> None:
        """The marks screen: every mark, and a jump to the one chosen."""
        self._marks.trim(self._store.first_seq)

        def chosen(seq: int | None) -> None:
            self._marks_changed()
            if seq is None:
                return
            if not self._table.jump_to_seq(seq):
                self._host.notify("That row is hidden by the rules (r shows them).", timeout=4)

        from ..screens.mark_list import MarksScreen  # loaded when first opened

        records = [self._store.get(seq) for seq in self._marks]
        shown = {record.seq for record in records if view_shows(self._view, record.seq)}
        self._host.push_screen(MarksScreen(records, shown, self._marks, utc=self._table.painter.utc), chosen)

    # -- the code file ----------------------------------------------------------------------------

    def open_code_file(self) -> None:
        """The selected message's code file in ``$VISUAL`` / ``$EDITOR``, at its line."""
        seq = self._table.cursor_seq
        if seq is None or seq not in self._store:
            return
        host = self._host
        record = self._store.get(seq)
        if not record.file:
            host.notify("This message names no source file.", timeout=4)
            return
        path, why = find_code_file(record.file, run_folders(self._opened_paths))
        if path is None:
            host.notify(why, severity="warning", timeout=8)
            return
        command, why = editor_command(path, record.line)
        if command is None:
            host.notify(why, severity="error", timeout=8)
            return
        try:
            with host.suspend():  # the terminal is the editor's until it exits
                result = run_editor(command)
        except SuspendNotSupported:  # no terminal to hand over (a headless run)
            result = run_editor(command, stdin=subprocess.DEVNULL)
        if isinstance(result, OSError):
            host.notify(f"Could not run the editor {one_line(command[0], 200)}: {result}", severity="error", timeout=8)
            return
        host.refresh()
        if result.returncode:
            host.notify(f"The editor exited with status {result.returncode}.", severity="warning", timeout=5)

    COMMANDS: ClassVar[tuple[Command[JumpsController], ...]] = (
        *(
            Command(
                f"nav.{name}",
                _seeking(level, forward),
                key,
                f"{'Next' if forward else 'Previous'} {Severity(level).name} or worse",
                group=NAVIGATION,
                title=f"{'Next' if forward else 'Previous'} {name.split('_')[-1]}",
                about=about,
            )
            for name, key, level, forward, about in (
                ("next_error", "e", 40, True, "The next ERROR or FATAL below"),
                ("previous_error", "E", 40, False, "The previous ERROR or FATAL above"),
                ("next_warning", "w", 30, True, "The next WARN or worse below"),
                ("previous_warning", "W", 30, False, "The previous WARN or worse above"),
            )
        ),
        Command("nav.first", first_row, keys_of="table.first", title="First message", about="The oldest row"),
        Command("nav.last", last_row, keys_of="table.follow", title="Last message", about="The newest row, and follow"),
        Command(
            "nav.mark",
            toggle_mark,
            "m",
            "Mark the row (or unmark it)",
            group=NAVIGATION,
            title="Mark the row",
            about="Put a mark on the selected row (or take it off)",
        ),
        Command(
            "nav.next_mark",
            lambda j: j.to_mark(forward=True),
            "u",
            "Next mark",
            group=NAVIGATION,
            about="The next marked row below",
        ),
        Command(
            "nav.previous_mark",
            lambda j: j.to_mark(forward=False),
            "U",
            "Previous mark",
            group=NAVIGATION,
            about="The previous marked row above",
        ),
        Command(
            "nav.marks",
            list_marks,
            "M",
            "Marks: list them, jump to one",
            group=NAVIGATION,
            title="Marks",
            about="Every marked row; go to one",
        ),
        Command(
            "nav.source",
            open_code_file,
            "v",
            "Open the row's source file in $VISUAL / $EDITOR",
            group=NAVIGATION,
            title="Open the source file",
            about="The row's file in $VISUAL / $EDITOR at its line",
            words="editor code vim",
        ),
    )
