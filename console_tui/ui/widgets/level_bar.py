"""Clickable level names under the logger list: a click sets the highlighted logger's level."""

from __future__ import annotations

from dataclasses import dataclass

from textual.message import Message
from textual.widgets import Static

from ...model.levels import SEVERITY_TABLE, Severity

#: The level ``Chosen`` carries for "temporary": ask for a level and a duration.
TEMPORARY = -1


class LevelBar(Static):
    """``DEBUG INFO WARN ERROR FATAL unset temporary``, each a link that posts ``Chosen``."""

    @dataclass
    class Chosen(Message):
        """A level name was clicked: ``level`` (0 unsets), or ``TEMPORARY``."""

        level: int

    def on_mount(self) -> None:
        parts = [f"[@click=choose({int(level.severity)})]{level.name}[/]" for level in SEVERITY_TABLE]
        parts.append(f"[@click=choose({int(Severity.UNSET)})]unset[/]")
        parts.append("[@click=temporary]temporary[/]")
        self.update(" ".join(parts))

    def action_choose(self, level: int) -> None:
        self.post_message(self.Chosen(level))

    def action_temporary(self) -> None:
        self.post_message(self.Chosen(TEMPORARY))
