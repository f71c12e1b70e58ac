"""The console's commands as data: each controller declares its own (``COMMANDS``), one row a
command, and the keys, the footer, the help screen, the command palette and whether a key
applies now are all read from the rows.

A row says what the command is called (``id``: ``keys.toml`` remaps its keys by it), what runs
(a function of the controller that declares it), its default keys and what its key does in a
few words (the footer and the help screen say it; these four in that order, as Textual's
``Binding`` takes a key, an action and a description), then by name: its place in the footer,
when it applies (the footer leaves it out, the key goes on to whatever else takes it), its entry
in the palette (a line of help, a title when not the label, other words people look for it by).
For example::

    Command("console.open", ask_open, "o", "Open", footer=30, about="Log files and recordings") Its key runs it as the action
``command('<id>')`` (``ConsoleApp.action_command``), and so does its palette entry.
(docs/decisions/0029-commands-as-data.md says why.)
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from textual.binding import Binding

#: The help screen's groups of the console's keys.
CONSOLE = "Console"
NAVIGATION = "Find your way"

Owner = TypeVar("Owner")


@dataclass(frozen=True)
class Command(Generic[Owner]):
    """One command, as the controller that runs it (``Owner``) declares it."""

    #: ``console.pause``: the name ``keys.toml`` and the help screen know it by.
    id: str
    #: What runs, given the controller.
    run: Callable[[Owner], object]
    #: Its keys (``"f,ctrl+f"``, Textual's names), or none: a palette entry only.
    keys: str = ""
    #: What the key does, in the footer and the help screen.
    label: str = ""
    #: Its place in the footer, left to right after the focused widget's keys (numbers ten
    #: apart, so that a new key goes between two), or 0: not in the footer.
    footer: int = 0
    #: Whether it applies now (None: always). A key that does not apply shows nowhere and
    #: goes on to whatever else takes it (Esc: the table's selection, a search, a filtering).
    applies: Callable[[Owner], bool] | None = None
    #: Its entry in the palette, when it has one: a line of help (none: not in the palette),
    #: a title (its label unless said), other words people look for it by (searched as the
    #: title is).
    about: str = ""
    title: str = ""
    words: str = ""
    #: It ends or undoes what another entry starts: it ranks below that one in the palette.
    ends: bool = False
    #: Its keys are another binding's, by id: space is Pause or Resume (one id, so that a
    #: keymap moves both), the palette's "Follow tail" names the table's own key.
    keys_of: str = ""
    #: Its group in the help screen.
    group: str = CONSOLE

    @property
    def palette_title(self) -> str:
        return self.title or self.label

    @property
    def action(self) -> str:
        return f"command({self.id!r})"

    @property
    def key_id(self) -> str:
        """The id of the binding whose keys run it (or show for it), or ""."""
        return self.keys_of or (self.id if self.keys else "")

    def binding(self) -> Binding:
        return Binding(self.keys, self.action, self.label, show=self.footer > 0, id=self.key_id)


def commands_of(owner: type) -> Sequence[Command[Any]]:
    """The rows a controller class declares."""
    commands: Sequence[Command[Any]] = getattr(owner, "COMMANDS", ())
    return commands


def key_bindings(commands: Iterable[Command[Any]]) -> list[Binding]:
    """The bindings of the rows that have keys, the footer's first in its order (Textual's
    footer shows the keys in the order they are bound)."""
    keyed = [command for command in commands if command.keys]
    shown = sorted((command for command in keyed if command.footer), key=lambda command: command.footer)
    return [command.binding() for command in (*shown, *(command for command in keyed if not command.footer))]


class CommandTable:
    """Every command of the console, each with the controller it runs on."""

    def __init__(self) -> None:
        self._rows: dict[str, tuple[Command[Any], object]] = {}

    def add(self, owner: object, commands: Iterable[Command[Any]] | None = None) -> None:
        """The rows of ``owner`` (its class's ``COMMANDS`` unless given), after those added before."""
        for command in commands_of(type(owner)) if commands is None else commands:
            if command.id in self._rows:
                raise ValueError(f"two commands are named {command.id!r}")
            self._rows[command.id] = (command, owner)

    def __iter__(self) -> Iterator[Command[Any]]:
        return (command for command, _owner in self._rows.values())

    def __contains__(self, command_id: object) -> bool:
        return command_id in self._rows

    def applies(self, command_id: str) -> bool:
        """Whether the command applies now (an unknown one never does)."""
        row = self._rows.get(command_id)
        if row is None:
            return False
        command, owner = row
        return command.applies is None or command.applies(owner)

    def run(self, command_id: str) -> None:
        command, owner = self._rows[command_id]
        command.run(owner)

    def state(self) -> tuple[bool, ...]:
        """Whether each command that comes and goes applies now: the footer is drawn again
        when this changes."""
        return tuple(command.applies(owner) for command, owner in self._rows.values() if command.applies is not None)

    def help_groups(self) -> list[tuple[str, list[Binding]]]:
        """The keyed commands by their group, in the table's order (a command that shares
        another's keys, Resume, is that one's row)."""
        groups: dict[str, list[Binding]] = {}
        for command in self:
            if command.keys and not command.keys_of:
                groups.setdefault(command.group, []).append(command.binding())
        return list(groups.items())

    def palette(self) -> list[Command[Any]]:
        """The palette's entries, in the order it lists them before anything is typed."""
        return [command for command in self if command.about]
