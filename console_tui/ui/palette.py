"""The command palette's entries (Ctrl+P): every command of the command table that has a title
(``command_table``), with its key as the bindings (and the user's keymap) say; an entry runs
its command's action, as its key does.

What a person types is looked for in the title, then in the words people use for the entry
(``words``: "search" finds Find, "editor" the source file), then in its help; an entry that
ends an action (``ends``: clear the search) ranks below the one that starts it.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from functools import partial
from typing import Any, Protocol, cast

from textual.binding import Binding
from textual.command import DiscoveryHit, Hit, Hits, Provider

from .command_table import Command, CommandTable
from .keys import KeyDisplay, key_label, keymap_of


class KeyedApp(KeyDisplay, Protocol):
    """What the palette reads of the app (``ConsoleApp``): its commands, its keys by where they work."""

    commands: CommandTable

    def binding_groups(self) -> list[tuple[str, list[Binding]]]: ...


class PaletteProvider(Provider):
    """The commands with a title, each shown with its key."""

    @property
    def console(self) -> KeyedApp:
        return cast(KeyedApp, self.app)  # only ConsoleApp lists this provider

    def _entries(self) -> Iterable[tuple[Command[Any], str]]:
        app = self.console
        bindings = {binding.id: binding for _title, group in app.binding_groups() for binding in group if binding.id}
        keymap = keymap_of(app)
        for command in app.commands.palette():
            binding = bindings.get(command.key_id) if command.key_id else None
            key = key_label(binding, app, keymap) if binding is not None else ""
            yield command, f"{command.about}  ({key})" if key else command.about

    async def discover(self) -> Hits:
        for command, help_text in self._entries():
            yield DiscoveryHit(command.palette_title, partial(self.app.run_action, command.action), help=help_text)

    async def search(self, query: str) -> Hits:
        matcher = self.matcher(query)
        for command, help_text in self._entries():
            score = palette_score(command, query, matcher.match)
            if score > 0:
                yield Hit(
                    score,
                    matcher.highlight(command.palette_title),
                    partial(self.app.run_action, command.action),
                    text=command.palette_title,
                    help=help_text,
                )


def _words(text: str) -> list[str]:
    return re.findall(r"[a-z0-9]+", text.lower())


def palette_score(command: Command[Any], query: str, fuzzy: Callable[[str], float]) -> float:
    """How well ``command`` answers what was typed (0: not at all): every typed word starting
    a word of the title scores highest, of its other words next, of its help after them; else
    the title's fuzzy match (``fuzzy``), lower. An entry that ends an action ranks lower."""
    typed = _words(query)

    def holds(text: str) -> bool:
        words = _words(text)
        return bool(typed) and all(any(word.startswith(part) for word in words) for part in typed)

    if holds(command.palette_title):
        score = 1.0
    elif holds(command.words):
        score = 0.9
    elif holds(command.about):
        score = 0.8
    else:
        score = 0.7 * fuzzy(command.palette_title)
    return score * 0.6 if command.ends else score
