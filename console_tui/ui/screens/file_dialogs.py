"""Dialogs for files: open (paths, with completion), save (where, which format, what)."""

from __future__ import annotations

import os
import shlex
from dataclasses import dataclass
from pathlib import Path

from textual import events, on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.suggester import Suggester
from textual.widgets import Checkbox, Input, Label, RadioButton, RadioSet

from ...model.formats.save import save_format_for
from ..keys import hint_line
from ..plain import plain
from ..widgets.marked_buttons import MarkedCheckbox, MarkedRadioButton

SAVE_FORMAT_TITLES = {
    "rqt": "rqt_console (ROS 2) .csv",
    "rqt1": "rqt_console (ROS 1) .csv",
    "jsonl": "JSON Lines, every field .jsonl",
}
SUFFIXES = {"rqt": ".csv", "rqt1": ".csv", "jsonl": ".jsonl"}


class PathSuggester(Suggester):
    """Completes the last path of the input from the file system (Tab or → accepts)."""

    def __init__(self) -> None:
        super().__init__(use_cache=False, case_sensitive=True)

    async def get_suggestion(self, value: str) -> str | None:
        _, _, last = value.rpartition(" ")
        if not last:
            return None
        expanded = os.path.expanduser(last)
        folder, prefix = os.path.split(expanded)
        try:
            names = sorted(n for n in os.listdir(folder or ".") if n.startswith(prefix) and not n.startswith("."))
        except OSError:
            return None
        if not names:
            return None
        completion = names[0][len(prefix) :]
        if os.path.isdir(os.path.join(folder or ".", names[0])):
            completion += "/"
        return value + completion if completion else None


class PathInput(Input):
    """A path box: Tab (or →) takes the completion shown after the text; Tab with none shown
    moves on to the next field.

    | Key(s) | Description |
    | :- | :- |
    | tab | Take the completion shown, or move on. |
    """

    BINDINGS = [Binding("tab", "complete", "Complete the path", show=False, id="path.complete")]

    def action_complete(self) -> None:
        suggestion = self._suggestion
        if len(suggestion) > len(self.value) and self.cursor_position >= len(self.value):
            self.value = suggestion
            self.cursor_position = len(suggestion)
        else:
            self.screen.focus_next()


class _Dialog(ModalScreen):
    """A title, the fields, a line of keys (from the bindings), and a line for what is wrong;
    long lines wrap, none is cut.

    | Key(s) | Description |
    | :- | :- |
    | escape | Cancel. |
    """

    DEFAULT_CSS = """
    _Dialog { align: center middle; }
    _Dialog > Vertical { width: 80; max-width: 95%; height: auto; border: thick $primary; background: $surface; padding: 0 1; }
    _Dialog Label { width: 100%; }
    _Dialog .title { text-style: bold; }
    _Dialog .hint { color: $text-muted; }
    _Dialog Input { margin: 1 0 0 0; }
    _Dialog .error { color: $text-error; }
    """
    BINDINGS = [Binding("escape", "cancel", "Cancel", id="dialog.cancel")]
    #: What Enter does, for the line of keys.
    ENTER_WORDS = "opens"

    def key_hints(self) -> str:
        """``tab completes · ⏎ opens · esc cancels``, from the bindings."""
        hints = [("complete", "completes"), ("submit", self.ENTER_WORDS), ("cancel", "cancels")]
        return hint_line(self.app, [*PathInput.BINDINGS, *Input.BINDINGS, *self.BINDINGS], hints)

    def error_line(self) -> Label:
        return Label("", classes="error", id="error", markup=False)

    def action_cancel(self) -> None:
        self.dismiss(None)


class OpenScreen(_Dialog):
    """Asks for files to open; returns their paths or None."""

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label("Open log files, recordings or folders", classes="title")
            yield PathInput(placeholder="~/.ros/log/...  run.bag  saved.csv", suggester=PathSuggester(), id="paths")
            yield Label(f"spaces separate files · {self.key_hints()}", classes="hint")
            yield self.error_line()

    @on(Input.Submitted)
    def submitted(self, event: Input.Submitted) -> None:
        try:
            paths = [os.path.expanduser(p) for p in shlex.split(event.value)]
        except ValueError as error:
            self.query_one("#error", Label).update(plain(f"Can't read that: {error}"))
            return
        missing = [p for p in paths if not os.path.exists(p)]
        if not paths or missing:
            self.query_one("#error", Label).update(plain(f"No such file: {missing[0]}" if missing else "Type a path"))
            return
        self.dismiss(paths)


class PathScreen(_Dialog):
    """Asks for one path (Tab completes); returns it, or None."""

    def __init__(self, title: str, default: str = "", *, must_exist: bool = False) -> None:
        super().__init__()
        self.title_text = title
        self.default = default
        self.must_exist = must_exist
        self.ENTER_WORDS = "opens" if must_exist else "saves"

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label(plain(self.title_text), classes="title")
            yield PathInput(self.default, suggester=PathSuggester(), id="path")
            yield Label(self.key_hints(), classes="hint")
            yield self.error_line()

    @on(Input.Submitted)
    def submitted(self, event: Input.Submitted) -> None:
        path = os.path.expanduser(event.value.strip())
        error = self.query_one("#error", Label)
        if not path:
            error.update("Type a path")
        elif self.must_exist and not os.path.isfile(path):
            error.update(plain(f"No such file: {path}"))
        elif not self.must_exist and not os.path.isdir(os.path.dirname(os.path.abspath(path))):
            error.update(plain(f"No such folder: {os.path.dirname(os.path.abspath(path))}"))
        else:
            self.dismiss(path)


@dataclass(frozen=True)
class SaveRequest:
    path: str
    save_format: str
    shown_only: bool


class SaveScreen(_Dialog):
    """Asks where and how to save; returns a ``SaveRequest`` or None."""

    ENTER_WORDS = "saves"

    def __init__(self, default_path: str, filtered: bool) -> None:
        super().__init__()
        self.default_path = default_path
        self.filtered = filtered

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label("Save messages to (the extension picks the format)", classes="title")
            yield PathInput(self.default_path, suggester=PathSuggester(), id="path")
            with RadioSet(id="format"):
                for key, title in SAVE_FORMAT_TITLES.items():
                    yield MarkedRadioButton(title, value=key == save_format_for(self.default_path), name=key)
            yield MarkedCheckbox(
                "Only the rows shown (after rules)", value=True, id="shown-only", disabled=not self.filtered
            )
            yield Label(self.key_hints(), classes="hint")
            yield self.error_line()

    @on(Input.Changed, "#path")
    def path_changed(self, event: Input.Changed) -> None:
        wanted = save_format_for(event.value)
        current = self._format()
        if wanted == "jsonl" or current == "jsonl":
            for button in self.query(RadioButton):
                if button.name == wanted and not button.value:
                    button.value = True

    @on(RadioSet.Changed)
    def format_changed(self, event: RadioSet.Changed) -> None:
        name = event.pressed.name or "rqt"
        path_input = self.query_one("#path", Input)
        path = Path(path_input.value)
        if save_format_for(path) == name:
            return  # the name as typed asks for this format (it was picked from the name): keep the name
        if path.suffix and path.suffix != SUFFIXES[name]:
            path_input.value = str(path.with_suffix(SUFFIXES[name]))

    def _format(self) -> str:
        pressed = self.query_one(RadioSet).pressed_button
        return (pressed.name if pressed is not None else None) or "rqt"

    def key_enter(self, event: events.Key) -> None:
        """Enter saves, wherever the focus is; the key stops here, so after the dialog closes
        it does not go on to the table (where Enter opens the detail view)."""
        event.stop()
        event.prevent_default()
        self.action_save()

    def action_save(self) -> None:
        path = os.path.expanduser(self.query_one("#path", Input).value.strip())
        error = self.query_one("#error", Label)
        if not path:
            error.update("Type a file name")
            return
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder):
            error.update(plain(f"No such folder: {folder}"))
            return
        if os.path.isdir(path):
            error.update(plain(f"{path} is a folder"))
            return
        shown_only = self.query_one("#shown-only", Checkbox).value and self.filtered
        self.dismiss(SaveRequest(path, self._format(), shown_only))
