"""Asking for a temporary level: which level, and for how many seconds."""

from __future__ import annotations

from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Input, OptionList, Static
from textual.widgets.option_list import Option

from ...model.levels import MESSAGE_SEVERITIES, Severity
from ..keys import Hint, hint_line
from ..plain import plain


class TemporaryLevelScreen(ModalScreen[tuple[int, float] | None]):
    """Which level, for how many seconds: returns ``(level, seconds)``, or None.

    | Key(s) | Description |
    | :- | :- |
    | escape | Cancel. |
    | up / down | The level above / below (DEBUG first); Enter in the seconds sets it. |
    """

    DEFAULT_CSS = """
    TemporaryLevelScreen { align: center middle; }
    TemporaryLevelScreen > Vertical {
        width: 56; max-width: 95%; height: auto; border: thick $primary; background: $surface; padding: 0 1;
    }
    TemporaryLevelScreen OptionList { height: auto; border: none; padding: 0; }
    TemporaryLevelScreen #temporary-error { color: $text-error; height: auto; }
    """
    BINDINGS = [
        Binding("escape", "cancel", "Cancel"),
        Binding("up", "level(-1)", "Level up", show=False),
        Binding("down", "level(1)", "Level down", show=False),
    ]

    def __init__(self, node: str, logger: str, seconds: float, level: int = Severity.DEBUG) -> None:
        super().__init__()
        self.node = node
        self.logger = logger
        self.seconds = seconds
        self.level = int(level)

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Static(plain(f"Temporary level for {self.logger} on {self.node}", style="bold"))
            yield OptionList(*(Option(s.name, id=s.name) for s in MESSAGE_SEVERITIES), id="temporary-levels")
            yield Static("For how many seconds (then the level before comes back):")
            yield Input(f"{self.seconds:g}", id="temporary-seconds", type="number")
            yield Static("", id="temporary-error")
            hints: list[Hint] = [(("level(-1)", "level(1)"), "level"), ("submit", "sets it"), ("cancel", "cancels")]
            yield Static(Text(hint_line(self.app, [*self.BINDINGS, *Input.BINDINGS], hints), style="dim"))

    def on_mount(self) -> None:
        levels = self.query_one(OptionList)
        levels.highlighted = [int(s) for s in MESSAGE_SEVERITIES].index(self.level)
        self.query_one(Input).focus()

    def action_level(self, step: int) -> None:
        levels = self.query_one(OptionList)
        levels.highlighted = max(0, min(len(MESSAGE_SEVERITIES) - 1, (levels.highlighted or 0) + step))

    def action_cancel(self) -> None:
        self.dismiss(None)

    @on(Input.Submitted)
    @on(OptionList.OptionSelected)
    def _apply(self) -> None:
        text = self.query_one(Input).value.strip()
        try:
            seconds = float(text)
        except ValueError:
            seconds = -1.0
        if not seconds > 0:
            self.query_one("#temporary-error", Static).update(plain(f"Seconds must be a number above 0, not {text!r}"))
            self.query_one(Input).focus()
            return
        highlighted = self.query_one(OptionList).highlighted or 0
        self.dismiss((int(MESSAGE_SEVERITIES[highlighted]), seconds))
