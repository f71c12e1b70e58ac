"""The help screen: what the tool shows and every key, read from the live bindings."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import VerticalScroll
from textual.screen import ModalScreen
from textual.widgets import Static

from ..keys import KeyDisplay, key_label, keymap_of, keymap_path

INTRO = (
    "console-tui shows every node's log messages in one table. It follows the newest "
    "message until you move up or pause; End follows again. Ctrl+P searches every action."
)


def keymap_note() -> str:
    path = str(keymap_path())
    home = str(Path.home())
    if path.startswith(home + os.sep):
        path = "~" + path[len(home) :]
    return f'Change keys in {path}, by the names on the right: console.pause = "p"'


def bindings_table(groups: list[tuple[str, list[Binding]]], app: KeyDisplay, keymap: Mapping[str, str]) -> Table:
    table = Table.grid(padding=(0, 2))
    table.add_column(style="bold", no_wrap=True)
    table.add_column()
    table.add_column(style="dim", no_wrap=True)
    for title, bindings in groups:
        table.add_row(Text(title, style="bold underline"), "", "")
        seen: set[str] = set()
        for binding in bindings:
            if binding.description in seen or not binding.description:
                continue
            seen.add(binding.description)
            table.add_row(key_label(binding, app, keymap), binding.description, binding.id or "")
        table.add_row("", "", "")
    return table


class HelpScreen(ModalScreen[None]):
    """Every key by where it works, with the name to remap it by.

    | Key(s) | Description |
    | :- | :- |
    | escape, q, question_mark, f1 | Close. |
    """

    DEFAULT_CSS = """
    HelpScreen { align: center middle; }
    HelpScreen > VerticalScroll {
        width: 96; max-width: 95%; height: 85%; border: thick $primary; background: $surface; padding: 1 0 1 2;
        scrollbar-size-vertical: 1;  /* at the box's edge, not a stray mark inside it */
    }
    HelpScreen .keymap-note { color: $text-muted; }
    """
    BINDINGS = [Binding("escape,q,question_mark,f1", "dismiss_screen", "Close")]

    def __init__(self, groups: list[tuple[str, list[Binding]]]) -> None:
        super().__init__()
        self.groups = groups

    def compose(self) -> ComposeResult:
        with VerticalScroll():
            yield Static(Text(INTRO), classes="intro")
            yield Static(Text(keymap_note()), classes="keymap-note")
            yield Static("")
            yield Static(bindings_table(self.groups, self.app, keymap_of(self.app)))

    def action_dismiss_screen(self) -> None:
        self.dismiss(None)
