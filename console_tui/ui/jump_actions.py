"""The app's jumps: next / previous error and warning, first / last message, marks, and
opening a message's source file in the user's editor.

A part of ``ConsoleApp`` (it mixes this in). A jump walks the history from the selected row
with the model's ``Seeker``: a few milliseconds at a time on the event loop, so a jump a
million rows away never freezes the screen.
"""

from __future__ import annotations

import subprocess
from collections.abc import Callable

from textual import work
from textual.app import SuspendNotSupported
from textual.binding import Binding

from ..model.levels import Severity
from ..model.marks import Marks
from ..model.seek import Hits, Seeker, level_hits, view_shows
from ..model.text import one_line
from .app_part import AppPart
from .screens.mark_list import MarksScreen
from .slicing import pause_between_slices
from .source_file import editor_command, find_source, run_editor, run_folders

#: A jump looks this long at once, then goes on in slices of the same length.
SEEK_BUDGET_S = 0.008
SEEK_PAUSE_S = 0.001


class JumpActions(AppPart):
    """Jumps to errors, warnings and marks; the source of a message in the editor."""

    # What it uses of the app (``ConsoleApp`` sets it).
    #: Every file and folder opened: where a message's bare file name may resolve.
    opened_paths: list[str]

    #: Its keys (``ConsoleApp.BINDINGS`` places them, for the footer's order).
    KEYS = [
        Binding("e", "next_level(40)", "Next ERROR or worse", show=False, id="nav.next_error"),
        Binding("E", "previous_level(40)", "Previous ERROR or worse", show=False, id="nav.previous_error"),
        Binding("w", "next_level(30)", "Next WARN or worse", show=False, id="nav.next_warning"),
        Binding("W", "previous_level(30)", "Previous WARN or worse", show=False, id="nav.previous_warning"),
        Binding("m", "toggle_mark", "Mark the row (or unmark it)", show=False, id="nav.mark"),
        Binding("u", "next_mark", "Next mark", show=False, id="nav.next_mark"),
        Binding("U", "previous_mark", "Previous mark", show=False, id="nav.previous_mark"),
        Binding("M", "marks", "Marks: list them, jump to one", show=False, id="nav.marks"),
        Binding("v", "open_source", "Open the row's source file in $VISUAL / $EDITOR", show=False, id="nav.source"),
    ]

    # What it uses of the app (``ConsoleApp`` sets them).
    marks: Marks
    _show_search_marks: Callable[[], None]

    # -- levels -----------------------------------------------------------------------------------

    def action_next_level(self, level: int) -> None:
        self._seek(level_hits(level), forward=True, what=f"{Severity(level).name} or worse")

    def action_previous_level(self, level: int) -> None:
        self._seek(level_hits(level), forward=False, what=f"{Severity(level).name} or worse")

    def action_first_row(self) -> None:
        self.table.action_first_row()

    def action_last_row(self) -> None:
        self.table.follow()

    def _seek(self, hits: Hits, *, forward: bool, what: str) -> None:
        seq = self.table.cursor_last_seq if forward else self.table.cursor_seq
        if seq is None:
            return
        seeker = Seeker(self.view, hits, seq, forward=forward, limit=self.table.paused_end)
        if seeker.step(SEEK_BUDGET_S):
            self._sought(seeker, what)
        else:
            self._seek_in_background(seeker, what)

    @work(exclusive=True, group="seek")
    async def _seek_in_background(self, seeker: Seeker, what: str) -> None:
        while not seeker.step(SEEK_BUDGET_S):
            await pause_between_slices(SEEK_PAUSE_S)
        self._sought(seeker, what)

    def _sought(self, seeker: Seeker, what: str) -> None:
        if seeker.found is not None:
            self.table.jump_to_seq(seeker.found)
        else:
            where = "below" if seeker.forward else "above"
            self.notify(f"No {what} {where}{'' if not seeker.failed else ': ' + seeker.failed}", timeout=3)

    # -- marks ------------------------------------------------------------------------------------

    def action_toggle_mark(self) -> None:
        seq = self.table.cursor_seq
        if seq is None:
            return
        self.marks.trim(self.store.first_seq)
        self.marks.toggle(seq)
        self._show_search_marks()  # the gutter shows marks and matches
        self.update_status()

    def action_next_mark(self) -> None:
        self._to_mark(forward=True)

    def action_previous_mark(self) -> None:
        self._to_mark(forward=False)

    def _to_mark(self, forward: bool) -> None:
        seq = self.table.cursor_last_seq if forward else self.table.cursor_seq
        self.marks.trim(self.store.first_seq)
        if seq is None or not len(self.marks):
            self.notify("No marks: m marks the selected row.", timeout=3)
            return
        limit = self.table.paused_end
        found = self.marks.nearest(
            seq, forward=forward, shown=lambda s: view_shows(self.view, s) and (limit is None or s < limit)
        )
        if found is None:
            self.notify(f"No mark {'below' if forward else 'above'} that the rules show.", timeout=3)
        else:
            self.table.jump_to_seq(found)

    def action_marks(self) -> None:
        self.marks.trim(self.store.first_seq)

        def chosen(seq: int | None) -> None:
            self._show_search_marks()
            if seq is None:
                return
            if not self.table.jump_to_seq(seq):
                self.notify("That row is hidden by the rules (r shows them).", timeout=4)

        records = [self.store.get(seq) for seq in self.marks]
        shown = {record.seq for record in records if view_shows(self.view, record.seq)}
        self.push_screen(MarksScreen(records, shown, self.marks, utc=self.table.utc), chosen)

    # -- the source file --------------------------------------------------------------------------

    def action_open_source(self) -> None:
        seq = self.table.cursor_seq
        if seq is None or seq not in self.store:
            return
        record = self.store.get(seq)
        if not record.file:
            self.notify("This message names no source file.", timeout=4)
            return
        path, why = find_source(record.file, run_folders(self.opened_paths))
        if path is None:
            self.notify(why, severity="warning", timeout=8)
            return
        command, why = editor_command(path, record.line)
        if command is None:
            self.notify(why, severity="error", timeout=8)
            return
        try:
            with self.suspend():  # the terminal is the editor's until it exits
                result = run_editor(command)
        except SuspendNotSupported:  # no terminal to hand over (a headless run)
            result = run_editor(command, stdin=subprocess.DEVNULL)
        if isinstance(result, OSError):
            self.notify(f"Could not run the editor {one_line(command[0], 200)}: {result}", severity="error", timeout=8)
            return
        self.refresh()
        if result.returncode:
            self.notify(f"The editor exited with status {result.returncode}.", severity="warning", timeout=5)
