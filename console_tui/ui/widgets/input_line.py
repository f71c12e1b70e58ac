"""A line of input at the foot of the screen, hidden until opened: what the search line and the
query line have in common."""

from __future__ import annotations

from textual.containers import Vertical
from textual.geometry import Size
from textual.widget import Widget
from textual.widgets import Input

from ..focus import focus_now


class LineInput(Input):
    """``Input`` whose typing does not lay out the screen.

    Textual's keeps its virtual size at its text's width through a reactive that lays out
    the whole screen on every key (in the turn of the search that key starts);
    a line's ``Input`` has a fixed size, so the width is set without a layout.
    """

    def _watch_value(self, value: str) -> None:
        self.set_reactive(Widget.virtual_size, Size(self.content_width, 1))
        super()._watch_value(value)  # sets the same size again: no change, no layout


class InputLine(Vertical):
    """One ``Input`` of one line (and what a subclass puts below it), shown while open.

    Subclasses compose the ``Input`` (a ``LineInput``) and say what its keys and messages mean.
    """

    DEFAULT_CSS = """
    InputLine { height: auto; display: none; background: $panel; padding: 0 1; }
    InputLine.-open { display: block; }
    /* One line, no border: the focused Input's built-in tall border must not win either. */
    InputLine > Input, InputLine > Input:focus { border: none; height: 1; padding: 0; background: $panel; }
    """

    @property
    def input(self) -> Input:
        return self.query_one(Input)

    @property
    def is_open(self) -> bool:
        return self.has_class("-open")

    def set_text(self, text: str) -> None:
        """The input's text, with the cursor at its end."""
        self.input.value = text
        self.input.cursor_position = len(text)

    def open_with(self, text: str) -> None:
        """Show the line holding ``text``, the focus in it."""
        self.add_class("-open")
        self.set_text(text)
        focus_now(self.input)

    def close(self) -> None:
        self.remove_class("-open")
