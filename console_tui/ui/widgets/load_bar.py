"""The loading line: which files are being read, how far, and how to cancel."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Label, ProgressBar

from ...model.text import plural
from ...sources.files import LoadProgress
from ..keys import hint_line
from ..plain import plain


class LoadBar(Horizontal):
    """Shown while files load; hidden otherwise."""

    DEFAULT_CSS = """
    LoadBar { height: 1; display: none; background: $panel; padding: 0 1; }
    LoadBar.-loading { display: block; }
    LoadBar > Label { width: 1fr; }
    LoadBar > ProgressBar { width: 50; }
    """

    def compose(self) -> ComposeResult:
        yield Label("", id="load-label")
        yield ProgressBar(total=1.0, show_eta=False, id="load-progress")

    def show_progress(self, progress: list[LoadProgress]) -> None:
        active = [p for p in progress if not p.finished]
        self.set_class(bool(active), "-loading")
        if not active:
            return
        files = [f for p in active for f in p.files]
        done = sum(1.0 if f.failed else f.fraction for f in files) / max(len(files), 1)
        records = sum(p.records for p in active)
        reading = next((f for f in files if not f.failed and f.fraction < 1.0), files[-1] if files else None)
        name = (
            f"{reading.source} ({reading.title})" if reading and reading.title else (reading.source if reading else "")
        )
        self.query_one(Label).update(
            plain(
                f"Loading {plural(len(files), 'file')}: {name}  {plural(records, 'record')}  "
                + hint_line(self.app, self.app.BINDINGS, [("cancel_load", "cancels")])
            )
        )
        self.query_one(ProgressBar).update(progress=done)
