"""Files: opening log files and recordings, their progress and problems, saving the table.

Files are read in the background (``sources.files.FileLoad``) into a queue of their own, which
the intake takes into the store ahead of live records.
"""

from __future__ import annotations

import asyncio
import os
import time
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, ClassVar

from ...model.inert_text import one_line, plural
from ...model.store.intake_queue import IntakeQueue
from ..command_table import Command
from ..widgets.load_bar import LoadBar
from .context import ConsoleContext

# Reading and writing files (the formats, the readers) and the dialogs load when first used,
# not with the first frame.
if TYPE_CHECKING:
    from ...sources.files import FileLoad
    from ..screens.file_dialogs import SaveRequest

#: Records gathered per event-loop turn when saving.
SAVE_SLICE = 20_000


class FilesController:
    """Files read in the background into the table, merged by time; the table saved to a file."""

    def __init__(
        self, context: ConsoleContext, load_bar: LoadBar, file_queue: IntakeQueue, *, log_format: str | None
    ) -> None:
        c = context
        self._host, self._store, self._view, self._table = c.host, c.store, c.view, c.table
        self._load_bar = load_bar
        #: File loads: their records come through a queue of their own, ahead of live ones.
        self._file_queue = file_queue
        #: The format to read files in, or None: found from each file.
        self._log_format = log_format
        self.loads: list[FileLoad] = []
        #: Every file and folder opened: the run's folders, where ``v`` looks for a bare file name.
        self.opened_paths: list[str] = []
        #: What went wrong while loading, for the problems screen.
        self.problems: list[str] = []
        #: How loaded files were read (local times, filled-in times), by source: the detail view says it.
        self.source_notes: dict[str, list[str]] = {}
        context.announce.tick.subscribe(self.check_loads)

    @property
    def loading(self) -> bool:
        """Files are being read, or their records are still on their way into the table."""
        return any(not load.finished for load in self.loads) or len(self._file_queue) > 0

    def open_files(self, paths: Sequence[str], *, robots: Mapping[str, str] | None = None) -> FileLoad:
        """Read files in the background into the table, merged by time, in the format given
        (``--format``) or found from each; ``robots``: the robot of each path (``--robot NAME``
        before it)."""
        from ...sources.files import FileLoad

        load = FileLoad(paths, self._file_queue, log_format=self._log_format, robots=robots)
        self.opened_paths.extend(paths)  # where ``v`` looks for a source file's bare name
        self.loads.append(load)
        load.start()
        self._table.set_column_shown("source", True)
        self._load_bar.show_progress([load.progress])
        return load

    def check_loads(self) -> None:
        """Progress on the load bar; a finished load says what it read, and what went wrong."""
        if not self.loads:
            return
        self._load_bar.show_progress([load.progress for load in self.loads])
        for load in [load for load in self.loads if load.finished]:
            if len(self._file_queue):
                return  # its last records are still on their way into the table
            self.loads.remove(load)
            progress = load.progress
            problems = [str(problem) for problem in load.problems()]
            self.problems.extend(problems)
            self.source_notes.update(load.notes())
            files = len(progress.files)
            verb = "Cancelled after" if progress.cancelled else "Loaded"
            text = f"{verb} {plural(progress.records, 'record')} from {plural(files, 'file')}"
            if progress.merged:
                text += f", {plural(progress.merged, 'repeat')} merged"  # in a rosout log and a node's own log
            if load.skipped:
                text += f" ({plural(len(load.skipped), 'other file')} in the folders passed over: empty, or not logs by name)"
            if problems:
                listed = "\n".join(one_line(problem, 300) for problem in problems[:3])
                more = f"\n... {len(problems) - 3} more" if len(problems) > 3 else ""
                self._host.notify(
                    f"{text}, with problems (! lists them):\n{listed}{more}", severity="warning", timeout=15
                )
            else:
                self._host.notify(text, timeout=5)

    def cancel_loads(self) -> None:
        for load in self.loads:
            load.cancel()

    def ask_open(self) -> None:
        def opened(paths: list[str] | None) -> None:
            if paths:
                self.open_files(paths)

        from ..screens.file_dialogs import OpenScreen

        self._host.push_screen(OpenScreen(), opened)

    def show_problems(self) -> None:
        from ..screens.load_problems import ProblemsScreen

        self._host.push_screen(ProblemsScreen(self.problems))

    def ask_save(self) -> None:
        default = os.path.join(os.getcwd(), time.strftime("console-tui-%Y%m%d-%H%M%S.csv"))

        def chosen(request: SaveRequest | None) -> None:
            if request is not None:
                self.save(request)

        from ..screens.file_dialogs import SaveScreen

        self._host.push_screen(SaveScreen(default, filtered=self._view.filtered), chosen)

    def save(self, request: SaveRequest) -> None:
        """Save in the background (``write``)."""
        self._host.run_worker(self.write(request), name="save", group="save", exclusive=True)

    async def write(self, request: SaveRequest) -> int:
        """Collect the rows on the UI thread a slice at a time (the store changes only
        here), then write them in a thread. Returns how many were written."""
        from ...model.formats.save import save_records  # the file formats load when first used

        seqs: Sequence[int]
        if request.shown_only:
            seqs = [self._view.seq_at(row) for row in range(len(self._view))]
        else:
            seqs = range(self._store.first_seq, self._store.end_seq)
        records = []
        for start in range(0, len(seqs), SAVE_SLICE):
            for seq in seqs[start : start + SAVE_SLICE]:
                if seq in self._store:
                    records.append(self._store.get(seq))
            await asyncio.sleep(0)
        lost = len(seqs) - len(records)
        try:
            written = await asyncio.to_thread(save_records, records, request.path, request.save_format)
        except (OSError, ValueError) as error:
            self._host.notify(f"Not saved: {error}", severity="error", timeout=15)
            return 0
        note = f" ({lost:,} dropped at the bound while saving)" if lost else ""
        self._host.notify(f"Saved {plural(written, 'message')} to {request.path}{note}", timeout=8)
        return written

    COMMANDS: ClassVar[tuple[Command[FilesController], ...]] = (
        Command(
            "console.open",
            ask_open,
            "o",
            "Open",
            footer=30,
            title="Open files",
            about="Log files and recordings, merged by time",
        ),
        Command(
            "console.save",
            ask_save,
            "s",
            "Save",
            footer=40,
            about="Save the rows shown, or everything (rqt_console CSV or JSON Lines)",
            words="export write",
        ),
        Command("console.cancel_load", cancel_loads, "x", "Cancel load", footer=50, applies=lambda f: f.loading),
        Command(
            "console.problems",
            show_problems,
            "exclamation_mark",
            "Problems",
            title="Load problems",
            about="What went wrong while loading files, and where",
        ),
    )
