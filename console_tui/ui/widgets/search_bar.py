"""The search line: type a text or a /regex/; the table goes to the nearest match as you type."""

from __future__ import annotations

from dataclasses import dataclass

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.message import Message
from textual.widgets import Input, Static

from ...model.rules.rule import RuleError
from ...model.view.search_walk import parse_search
from ..keys import Hint, hint_line
from ..plain import plain
from .input_line import InputLine, LineInput

PLACEHOLDER = "text to find (smart case), or /regex/ or /regex/i: the rows stay, matches are marked"


class SearchBar(InputLine):
    """Hidden until opened. Posts ``Changed`` as the text changes and ``Done`` when closed.

    | Key(s) | Description |
    | :- | :- |
    | escape | Cancel the search, the cursor back where it was. |
    """

    DEFAULT_CSS = """
    SearchBar > #search-hint { color: $text-muted; height: auto; }
    SearchBar > #search-hint.-error { color: $text-error; }
    """

    BINDINGS = [Binding("escape", "cancel", "Cancel the search", show=False, id="search.cancel")]

    @dataclass
    class Changed(Message):
        """The text changed and reads as a search (or is empty)."""

        text: str

    @dataclass
    class Done(Message):
        """Enter (``keep``: the search stays) or Escape (cancelled)."""

        keep: bool

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.text = ""
        self._hint_shown: tuple[str, str] | None = None

    def compose(self) -> ComposeResult:
        yield LineInput(placeholder=PLACEHOLDER, id="search-input")
        yield Static("", id="search-hint")

    def on_mount(self) -> None:
        self.show_hint()

    def key_hints(self) -> str:
        """``⏎ keeps the search · esc cancels · n/N next/previous afterwards``, from the bindings."""
        hints: list[Hint] = [("submit", "keeps the search"), ("cancel", "cancels")]
        line = hint_line(self.app, [*self.BINDINGS, *Input.BINDINGS], hints)
        more = hint_line(
            self.app, self.app.BINDINGS, [(("nav.next_match", "nav.previous_match"), "next/previous afterwards")]
        )
        return " · ".join(part for part in (line, more) if part)

    def show_hint(self, problem: str = "") -> None:
        """The problem with the text typed, or the keys; the same text is not set again (each
        update lays the screen out again, and this runs on every key typed)."""
        shown = (problem, "" if problem else self.key_hints())
        if shown == self._hint_shown:
            return
        self._hint_shown = shown
        hint = self.query_one("#search-hint", Static)
        hint.set_class(bool(problem), "-error")
        hint.update(plain(problem) if problem else shown[1])

    def open(self, text: str = "") -> None:
        self.show_hint()
        self.open_with(text)

    def action_cancel(self) -> None:
        self.close()
        self.post_message(self.Done(keep=False))

    @on(Input.Changed, "#search-input")
    def changed(self, event: Input.Changed) -> None:
        event.stop()
        try:
            parse_search(event.value)
        except RuleError as error:
            self.show_hint(error.message)
            return
        self.show_hint()
        self.text = event.value
        self.post_message(self.Changed(event.value))

    @on(Input.Submitted, "#search-input")
    def submitted(self, event: Input.Submitted) -> None:
        event.stop()
        try:
            parse_search(event.value)
        except RuleError:
            return  # the problem is shown; Esc cancels
        self.close()
        self.post_message(self.Done(keep=True))
