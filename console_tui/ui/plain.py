"""Text from outside (file names, paths, node and logger names, errors from nodes and files)
for widgets: never read as markup, never sent to the terminal raw.

Textual reads a ``str`` given to a Label, a Static or an Option as markup, so ``[/]`` in a
file name is a crash and ``[@click=...]`` an action; Rich passes ESC through to the
terminal. ``plain`` gives a ``Text`` (not markup) of the inert form (``model.inert_text``).
"""

from __future__ import annotations

from typing import Any

from rich.text import Text

from ..model.inert_text import multi_line, one_line


def plain(text: str, *, limit: int | None = 1000, lines: bool = False, **options: Any) -> Text:
    """``text`` as inert, literal ``Text``: on one line (cut to ``limit``), or with its own
    line breaks kept (``lines``); ``options`` go to ``Text`` (style, no_wrap, overflow)."""
    return Text(multi_line(text) if lines else one_line(text, limit), **options)
