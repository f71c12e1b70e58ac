"""Check boxes and radio buttons whose mark shows only when they are on.

Textual's draw the same mark (``X``, ``●``) whether on or off and tell the two apart by
colour alone: with ``NO_COLOR`` (or on a monochrome terminal) every box looked ticked and
every format chosen. These draw the mark when on and a blank when off, in every colour
mode.
"""

from __future__ import annotations

from textual.content import Content
from textual.widgets import Checkbox, RadioButton


class MarkedCheckbox(Checkbox):
    """A ``Checkbox`` that draws ``X`` when ticked and a blank when not."""

    MARK = "X"

    def render(self) -> Content:
        self.BUTTON_INNER = self.MARK if self.value else " "
        return super().render()


class MarkedRadioButton(RadioButton):
    """A ``RadioButton`` that draws ``●`` when chosen and a blank when not."""

    MARK = "\u25cf"

    def render(self) -> Content:
        self.BUTTON_INNER = self.MARK if self.value else " "
        return super().render()
