"""The loading line: which files are being read, how far, and how to cancel."""

from __future__ import annotations

from typing import TYPE_CHECKING

from textual.app import ComposeResult
from textual.containers import Horizontal
from textual.widgets import Label, ProgressBar

from ...model.inert_text import plural
from ..keys import hint_line
from ..plain import plain

if TYPE_CHECKING:  # the file readers load when a file is first opened
    from ...sources.files import LoadProgress


class LoadBar(Horizontal):
    """Shown while files load; hidden otherwise."""

    DEFAULT_CSS = """
    LoadBar { height: 1; display: none; background: $panel; padding: 0 1; }
    LoadBar.-loading { display: block; }
    LoadBar > Label { width: 1fr; height: 1; text-wrap: nowrap; text-overflow: ellipsis; }
    LoadBar > ProgressBar { width: 36; }
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
        opened = sum(1 for f in files if f.title or f.failed or f.fraction > 0)
        if any(p.searching for p in active):
            what = f"Looking for logs in {', '.join(_tail(f.source) for f in files[:3])}"
        elif opened < len(files):  # a folder's logs are being opened
            what = f"Opening {opened:,} of {plural(len(files), 'file')}"
        else:
            started = [f for f in files if not f.failed and 0.0 < f.fraction < 1.0]
            reading = next(iter(started), None) or next((f for f in files if not f.failed and f.fraction < 1.0), None)
            name = reading.source.rsplit("/", 1)[-1] if reading else ""
            what = f"Loading {plural(len(files), 'file')}: {name}"
        hint = hint_line(self.app, self.app.BINDINGS, [("console.cancel_load", "cancels")])
        self.query_one(Label).update(plain(f"{what}  {plural(records, 'record')}  {hint}"))
        self.query_one(ProgressBar).update(progress=done)


def _tail(source: str, limit: int = 32) -> str:
    """A source name short enough for the line: its end, where the file's name is."""
    return source if len(source) <= limit else "…" + source[-(limit - 1) :]
