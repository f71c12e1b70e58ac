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

_HINTS: list[Hint] = [("toggle_column", "shows or hides"), ("apply", "applies"), ("cancel", "cancels")]


class ColumnList(SelectionList[str], inherit_bindings=False):
    """The columns, each shown or hidden with space. Enter is left to the dialog (a selection
    list would take it as "toggle"), and space toggles at once (a selection list does it a
    message later), so that Enter typed right behind them applies what they chose.

    | Key(s) | Description |
    | :- | :- |
    | up / down | Move the highlight. |
    | home / end | The first / last column. |
    | pageup / pagedown | A page up / down. |
    | space | Show or hide the highlighted column. |
    """

    BINDINGS = [
        Binding("down", "cursor_down", "Down", show=False),
        Binding("up", "cursor_up", "Up", show=False),
        Binding("home", "first", "First", show=False),
        Binding("end", "last", "Last", show=False),
        Binding("pagedown", "page_down", "Page Down", show=False),
        Binding("pageup", "page_up", "Page Up", show=False),
        Binding("space", "toggle_column", "Show or hide", show=False, id="columns.toggle"),
    ]

    def action_toggle_column(self) -> None:
        if self.highlighted is None:
            return
        option = self.get_option_at_index(self.highlighted)
        if not option.disabled:
            self.toggle(option)


class ColumnsScreen(ModalScreen[frozenset[str] | None]):
    """Space shows or hides the highlighted column, Enter applies and closes, Escape cancels.

    | Key(s) | Description |
    | :- | :- |
    | escape | Cancel. |
    | enter | Apply and close. |
    """

    DEFAULT_CSS = """
    ColumnsScreen { align: center middle; }
    ColumnsScreen > Vertical {
        width: auto; height: auto; max-width: 95%;
        border: thick $primary; background: $surface; padding: 0 1;
    }
    ColumnsScreen Label { width: auto; }
    ColumnsScreen ColumnList { height: auto; width: 100%; }
    ColumnsScreen #columns-hint { color: $text-muted; }
    """
    BINDINGS = [
        Binding("escape", "cancel", "Cancel", id="columns.cancel"),
        Binding("enter", "apply", "Apply", id="columns.apply"),
    ]

    def __init__(self, shown: frozenset[str]) -> None:
        super().__init__()
        self.shown = shown

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label("Columns shown", id="columns-title")
            yield ColumnList(
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
            yield Label(self.key_hints(), id="columns-hint")

    def key_hints(self) -> str:
        """``space shows or hides · ⏎ applies · esc cancels``, from the bindings."""
        return hint_line(self.app, [*self.BINDINGS, *ColumnList.BINDINGS], _HINTS)

    def action_apply(self) -> None:
        selected = frozenset(self.query_one(ColumnList).selected) | {"message"}
        self.dismiss(frozenset(selected))

    def action_cancel(self) -> None:
        self.dismiss(None)
