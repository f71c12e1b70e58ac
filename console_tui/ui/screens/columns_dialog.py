"""Choosing which table columns are shown."""

from __future__ import annotations

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Label, SelectionList
from textual.widgets.selection_list import Selection

from ..keys import Hint, hint_line
from ..widgets.table_columns import COLUMNS

_HINTS: list[Hint] = [("select", "toggles"), ("apply", "applies"), ("cancel", "cancels")]


class ColumnsScreen(ModalScreen[frozenset[str] | None]):
    """Which table columns are shown: space toggles one.

    | Key(s) | Description |
    | :- | :- |
    | escape | Cancel. |
    | enter | Apply. |
    """

    DEFAULT_CSS = """
    ColumnsScreen { align: center middle; }
    ColumnsScreen > Vertical { width: 48; height: auto; border: thick $primary; background: $surface; padding: 0 1; }
    ColumnsScreen SelectionList { height: auto; }
    ColumnsScreen .title { text-style: bold; }
    ColumnsScreen .hint { color: $text-muted; }
    """
    BINDINGS = [Binding("escape", "cancel", "Cancel"), Binding("enter", "apply", "Apply")]

    def __init__(self, shown: frozenset[str]) -> None:
        super().__init__()
        self.shown = shown

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label("Columns", classes="title")
            yield SelectionList[str](
                *(
                    Selection(
                        column.title if column.key != "seq" else "# (number)",
                        column.key,
                        column.key in self.shown,
                        disabled=column.key == "message",
                    )
                    for column in COLUMNS
                )
            )
            yield Label(hint_line(self.app, [*SelectionList.BINDINGS, *self.BINDINGS], _HINTS), classes="hint")

    def action_apply(self) -> None:
        selected = frozenset(self.query_one(SelectionList).selected) | {"message"}
        self.dismiss(frozenset(selected))

    def action_cancel(self) -> None:
        self.dismiss(None)
