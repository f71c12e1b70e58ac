"""Every problem met while loading files: what, and where."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Label, Log

from ...model.inert_text import one_line, plural


class ProblemsScreen(ModalScreen[None]):
    """What went wrong while loading files, and where.

    | Key(s) | Description |
    | :- | :- |
    | escape, q | Close. |
    """

    DEFAULT_CSS = """
    ProblemsScreen { align: center middle; }
    ProblemsScreen > Vertical { width: 90%; height: 70%; border: thick $error; background: $surface; padding: 0 1; }
    ProblemsScreen Log { height: 1fr; }
    """
    BINDINGS = [Binding("escape,q", "close", "Close")]

    def __init__(self, problems: list[str]) -> None:
        super().__init__()
        self.problems = problems

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label(f"{plural(len(self.problems), 'problem')} while loading (Escape closes)")
            log = Log(highlight=False)
            yield log

    def on_mount(self) -> None:
        log = self.query_one(Log)
        log.write_lines([one_line(problem, 2000) for problem in self.problems] or ["No problems."])

    def action_close(self) -> None:
        self.dismiss(None)
