"""The query line: type rules as text, see mistakes as you type, Enter applies."""

from __future__ import annotations

from dataclasses import dataclass

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.message import Message
from textual.widgets import Input, Static

from ...model.inert_text import one_line, plural
from ...model.rules.history import QueryHistory
from ...model.rules.query import QueryError, caret_line, parse_query
from ...model.rules.ruleset import Entry
from ..keys import Hint, hint_line
from ..plain import plain
from .input_line import InputLine, LineInput

_HINTS: list[Hint] = [("submit", "applies"), ("close", "closes"), (("history(-1)", "history(1)"), "history")]
PLACEHOLDER = 'level>=warn node:nav* -node:rviz* +"planner failed" /time(out|d out)/i file:planner.cpp'


class QueryBar(InputLine):
    """Hidden until opened; while the text does not parse, the rules in force stay.

    | Key(s) | Description |
    | :- | :- |
    | escape | Close (``Closed``). |
    | up / down | An earlier / a later query from the history. |
    """

    DEFAULT_CSS = """
    QueryBar > #query-problem { color: $text-error; height: auto; }
    QueryBar > #query-problem.-ok { color: $text-muted; }
    """

    BINDINGS = [
        Binding("escape", "close", "Close", show=False, id="query.close"),
        Binding("up", "history(-1)", "Earlier query", show=False, id="query.earlier"),
        Binding("down", "history(1)", "Later query", show=False, id="query.later"),
    ]

    @dataclass
    class Applied(Message):
        """Enter on a query that parses: its entries replace the previous query's."""

        text: str
        entries: tuple[Entry, ...]

    class Closed(Message):
        """Escape (or after applying): focus goes back to the table."""

    def __init__(self, history: QueryHistory, *, utc: bool = False, id: str | None = None) -> None:
        super().__init__(id=id)
        self.history = history
        self.utc = utc
        self.applied_text = ""

    def compose(self) -> ComposeResult:
        yield LineInput(placeholder=PLACEHOLDER, id="query-input")
        yield Static(f"{self.key_hints()} · -term excludes, +term highlights", id="query-problem", classes="-ok")

    def key_hints(self) -> str:
        """``⏎ applies · esc closes · ↑/↓ history``, from the bindings."""
        return hint_line(self.app, [*self.BINDINGS, *Input.BINDINGS], _HINTS)

    def open(self) -> None:
        self.open_with(self.applied_text)

    def action_close(self) -> None:
        self.close()
        self.post_message(self.Closed())

    def action_history(self, step: int) -> None:
        current = self.input.value
        found = self.history.previous(current) if step < 0 else self.history.following()
        if found is not None and found == current and step < 0:
            found = self.history.previous(current) or found  # the query shown is the newest: skip it
        if found is not None:
            self.set_text(found)

    def check(self, text: str) -> tuple[Entry, ...] | None:
        """The entries of ``text``, or None after showing where it goes wrong."""
        problem = self.query_one("#query-problem", Static)
        try:
            entries = parse_query(text, utc=self.utc)
        except QueryError as error:
            problem.remove_class("-ok")
            caret = caret_line(one_line(text), error)
            problem.update(plain(f"{caret}\n(the rules in force stay until the query is fixed)", lines=True))
            return None
        problem.add_class("-ok")
        count = len(entries)
        problem.update(f"{plural(count, 'rule')} · {self.key_hints()}")
        return entries

    @on(Input.Changed, "#query-input")
    def changed(self, event: Input.Changed) -> None:
        self.check(event.value)

    @on(Input.Submitted, "#query-input")
    def submitted(self, event: Input.Submitted) -> None:
        entries = self.check(event.value)
        if entries is None:
            return
        self.applied_text = event.value.strip()
        self.history.add(self.applied_text)
        self.post_message(self.Applied(self.applied_text, entries))
        self.action_close()
