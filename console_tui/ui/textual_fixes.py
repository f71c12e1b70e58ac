"""Work-arounds for Textual bugs, until they are fixed upstream (each with a test).

- ``OptionList._move_page`` (PageUp/PageDown) looks up the highlighted option's line in a
  table that is only built once the list has a size: on a list with options, one
  highlighted, but no size yet (the command palette's while its results come in), it ends
  in ``KeyError: 0`` and the app exits. Here such a page move goes to the first or last
  option instead. Seen with Textual 8.2.8 (Ctrl+P, then PageUp).
"""

from __future__ import annotations

from textual.widgets import OptionList

_original_move_page = OptionList._move_page


def _move_page(self: OptionList, direction: int) -> None:
    try:
        _original_move_page(self, direction)  # type: ignore[arg-type]
    except (KeyError, IndexError):  # no lines laid out yet
        if direction < 0:
            self.action_first()
        else:
            self.action_last()


def apply() -> None:
    """Install the work-arounds (idempotent)."""
    OptionList._move_page = _move_page  # type: ignore[method-assign]
