"""Every field of one record, and its whole message, inert."""

from __future__ import annotations

from collections.abc import Callable, Mapping

from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Footer, Static, TextArea

from ...model.formats.mixed_output import LOCAL_TIME_NOTE
from ...model.inert_text import multi_line, one_line, plural
from ...model.levels import severity_name
from ...model.store.record import LogRecord
from ...model.timefmt import full_text, stamp_text
from ..focus import focus_now

FIELD_LIMIT = 500
#: Soft wrapping a longer line takes seconds in TextArea: such messages open unwrapped.
WRAP_LIMIT = 20_000


def wraps_quickly(text: str) -> bool:
    return max((len(line) for line in text.split("\n")), default=0) <= WRAP_LIMIT


def fields_table(record: LogRecord, *, utc: bool = False, notes: tuple[str, ...] | list[str] = ()) -> Table:
    """The record's fields; ``notes`` are what the reader of its file said about how it was read."""
    table = Table.grid(padding=(0, 2))
    table.add_column(style="bold", no_wrap=True)
    table.add_column(overflow="fold")
    time_text = full_text(record.stamp_ns, utc=utc)
    if any(note.startswith(LOCAL_TIME_NOTE) for note in notes):
        time_text += "  (the file's local time: it gives no zone)"
    rows = [
        ("#", str(record.seq + 1)),
        ("Time", time_text),
        ("Stamp", stamp_text(record.stamp_ns)),
        ("Severity", f"{severity_name(record.level)} ({record.level})"),
        *([("Robot", record.robot)] if record.robot else []),
        ("Node", record.node),
        ("File", record.file),
        ("Function", record.function),
        ("Line", str(record.line)),
        ("Source", record.source),
        *([("Topics", record.topics.replace(",", ", "))] if record.topics else []),
        ("Length", f"{plural(len(record.msg), 'character')}, {plural(record.msg.count(chr(10)) + 1, 'line')}"),
    ]
    rows += [("File notes" if index == 0 else "", note) for index, note in enumerate(notes)]
    for name, value in rows:
        table.add_row(name, Text(one_line(value, FIELD_LIMIT)))
    return table


class DetailScreen(ModalScreen[None]):
    """A record's fields and its full multi-line message; n and p step through the table's rows.

    | Key(s) | Description |
    | :- | :- |
    | escape, q | Close. |
    | n / p | The next / previous row. |
    | w | Wrap the message, or not. |
    | y | Copy the message. |
    """

    DEFAULT_CSS = """
    DetailScreen { align: center middle; }
    DetailScreen > Vertical {
        width: 90%; height: 90%; border: thick $primary; background: $surface; padding: 0 1;
    }
    DetailScreen #fields { height: auto; margin-bottom: 1; }
    DetailScreen TextArea { height: 1fr; }
    """

    BINDINGS = [
        Binding("escape,q", "dismiss_screen", "Close", id="detail.close"),
        Binding("n", "step(1)", "Next row", id="detail.next"),
        Binding("p", "step(-1)", "Previous row", id="detail.previous"),
        Binding("w", "toggle_wrap", "Wrap", id="detail.wrap"),
        Binding("y", "copy", "Copy message", id="detail.copy"),
    ]

    def __init__(
        self,
        record: LogRecord,
        *,
        utc: bool = False,
        step: Callable[[int, int], LogRecord | None] | None = None,
        source_notes: Mapping[str, list[str]] | None = None,
    ) -> None:
        super().__init__()
        self.record = record
        self.utc = utc
        self._step = step
        self._source_notes = source_notes or {}

    def _fields(self, record: LogRecord) -> Table:
        return fields_table(record, utc=self.utc, notes=self._source_notes.get(record.source, ()))

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Static(self._fields(self.record), id="fields")
            text = multi_line(self.record.msg)
            area = TextArea(text, read_only=True, soft_wrap=wraps_quickly(text), id="message")
            area.show_line_numbers = True
            yield area
        yield Footer()

    def on_mount(self) -> None:
        focus_now(self.query_one(TextArea))

    def show(self, record: LogRecord) -> None:
        self.record = record
        self.query_one("#fields", Static).update(self._fields(record))
        text = multi_line(record.msg)
        area = self.query_one(TextArea)
        area.soft_wrap = wraps_quickly(text)
        area.load_text(text)

    def action_dismiss_screen(self) -> None:
        self.dismiss(None)

    def action_step(self, delta: int) -> None:
        if self._step is None:
            return
        record = self._step(self.record.seq, delta)
        if record is not None:
            self.show(record)

    def action_toggle_wrap(self) -> None:
        area = self.query_one(TextArea)
        area.soft_wrap = not area.soft_wrap

    def action_copy(self) -> None:
        self.app.copy_to_clipboard(self.record.msg)
        self.notify("Message copied (OSC 52)", timeout=2)
