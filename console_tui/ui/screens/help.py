"""The help screen: what the tool shows and every key, read from the live bindings."""

from __future__ import annotations

from collections.abc import Callable

from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Static

INTRO = (
    "console-tui shows every node's log messages in one table. It follows the newest "
    "message until you move up or pause; End follows again. Ctrl+P searches every action."
)


def key_label(binding: Binding, display: Callable[[Binding], str]) -> str:
    """Every key of a binding as the footer shows keys: ``?, f1``."""
    keys = [part.strip() for part in binding.key.split(",") if part.strip()]
    return ", ".join(display(Binding(key, binding.action)) for key in keys)


def bindings_table(groups: list[tuple[str, list[Binding]]], display: Callable[[Binding], str]) -> Table:
    table = Table.grid(padding=(0, 2))
    table.add_column(style="bold cyan", no_wrap=True)
    table.add_column()
    for title, bindings in groups:
        table.add_row(Text(title, style="bold underline"), "")
        seen: set[str] = set()
        for binding in bindings:
            if binding.description in seen or not binding.description:
                continue
            seen.add(binding.description)
            table.add_row(key_label(binding, display), binding.description)
        table.add_row("", "")
    return table


class HelpScreen(ModalScreen[None]):
    DEFAULT_CSS = """
    HelpScreen { align: center middle; }
    HelpScreen > VerticalScroll {
        width: 80; max-width: 95%; height: 85%; border: thick $primary; background: $surface; padding: 1 2;
    }
    """
    BINDINGS = [Binding("escape,q,question_mark,f1", "dismiss_screen", "Close")]

    def __init__(self, groups: list[tuple[str, list[Binding]]]) -> None:
        super().__init__()
        self.groups = groups

    def compose(self) -> ComposeResult:
        with VerticalScroll():
            yield Static(Text(INTRO), classes="intro")
            yield Static("")
            yield Static(bindings_table(self.groups, self.app.get_key_display))

    def action_dismiss_screen(self) -> None:
        self.dismiss(None)
