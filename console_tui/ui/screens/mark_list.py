"""The marks: every marked row, oldest first; Enter goes to one, d takes a mark off."""

from __future__ import annotations

from typing import cast

from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Label, OptionList, Static
from textual.widgets.option_list import Option

from ...model.inert_text import one_line, plural
from ...model.levels import severity_name
from ...model.store.record import LogRecord
from ...model.timefmt import clock_text
from ...model.view.marks import Marks
from ..keys import Hint, KeyDisplay, hint_line, key_label, keymap_of

_HINTS: list[Hint] = [("go", "goes to it"), ("unmark", "takes the mark off"), ("close", "closes")]


def mark_line(record: LogRecord, shown: bool, utc: bool) -> Table:
    """One mark: its row number, time, severity, node and message, on one line."""
    head = Text(no_wrap=True)
    head.append(f"{record.seq + 1:>7} ", style="dim")
    head.append(clock_text(record.stamp_ns, utc=utc) + " ", style="dim")
    head.append(f"{severity_name(record.level):<5} ", style="bold")
    head.append(one_line(record.node, 40), style="cyan")
    message = Text(one_line(record.msg, 300), no_wrap=True, overflow="ellipsis")
    if not shown:
        message.append("  (hidden by the rules)", style="italic dim")
    grid = Table.grid(expand=True, padding=(0, 1))
    grid.add_column(no_wrap=True)
    grid.add_column(ratio=1, no_wrap=True, overflow="ellipsis")
    grid.add_row(head, message)
    return grid


def marks_title(count: int, mark_key: str = "m") -> str:
    return plural(count, "mark") if count else f"No marks: {mark_key} on a row marks it."


def mark_key(app: object) -> str:
    """The key that marks a row, as the keymap has it (``ConsoleApp.binding_groups``)."""
    groups = getattr(app, "binding_groups", None)
    for _title, bindings in groups() if callable(groups) else ():
        for binding in bindings:
            if binding.id == "nav.mark":
                return key_label(binding, cast(KeyDisplay, app), keymap_of(app), first_only=True)
    return "m"


class MarksScreen(ModalScreen[int | None]):
    """Lists the marks; dismissed with the seq to go to, or None.

    | Key(s) | Description |
    | :- | :- |
    | enter | Go to the highlighted mark. |
    | d, delete | Take its mark off. |
    | escape, q, M | Close. |
    """

    DEFAULT_CSS = """
    MarksScreen { align: center middle; }
    MarksScreen > Vertical {
        width: 90%; height: auto; max-height: 80%; border: thick $primary; background: $surface; padding: 0 1;
    }
    MarksScreen OptionList { height: auto; max-height: 60vh; border: none; }
    MarksScreen #marks-hint { color: $text-muted; height: auto; }
    """
    BINDINGS = [
        Binding("enter", "go", "Go to the mark", show=False, id="marks.go"),
        Binding("d,delete", "unmark", "Take the mark off", show=False, id="marks.unmark"),
        Binding("escape,q,M", "close", "Close", show=False, id="marks.close"),
    ]

    def __init__(self, records: list[LogRecord], shown: set[int], marks: Marks, *, utc: bool = False) -> None:
        super().__init__()
        self.records = records
        self.shown = shown
        self.marks = marks
        self.utc = utc

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label(marks_title(len(self.records), mark_key(self.app)))
            yield OptionList(
                *(Option(mark_line(r, r.seq in self.shown, self.utc), id=str(r.seq)) for r in self.records),
                id="marks-list",
            )
            yield Static(hint_line(self.app, self.BINDINGS, _HINTS), id="marks-hint")

    def _highlighted_seq(self) -> int | None:
        options = self.query_one(OptionList)
        if options.highlighted is None or not options.option_count:
            return None
        option_id = options.get_option_at_index(options.highlighted).id
        return int(option_id) if option_id is not None else None

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self.action_go()

    def action_go(self) -> None:
        self.dismiss(self._highlighted_seq())

    def action_unmark(self) -> None:
        seq = self._highlighted_seq()
        if seq is None:
            return
        self.marks.discard(seq)
        options = self.query_one(OptionList)
        options.remove_option(str(seq))
        self.query_one(Label).update(marks_title(len(self.marks), mark_key(self.app)))

    def action_close(self) -> None:
        self.dismiss(None)
