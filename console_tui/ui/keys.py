"""Keys: the user's keymap file, and key hints and help rows read from the bindings.

Every binding a user may want to move has an id (``console.pause``, ``table.follow``,
``loggers.debug``...). ``$XDG_CONFIG_HOME/console-tui/keys.toml`` maps ids to keys::

    [console]
    pause = "p"              # console.pause
    quit = ["q", "ctrl+q"]

    [loggers]
    debug = "D"

Hints and the help screen read the keys from the bindings through the keymap, so a key is
written once, in its ``Binding``, and what the screen says follows a remapping.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

from textual.binding import Binding, BindingType

from ..model.rules.rulesfile import config_dir
from ..model.toml_text import TomlError, loads_toml

KEYMAP_FILE = "keys.toml"


def keymap_path() -> Path:
    return config_dir() / KEYMAP_FILE


@dataclass(frozen=True)
class LoadedKeymap:
    """Binding id -> keys (``"p"``, ``"q,ctrl+q"``), and what was wrong in the file."""

    keys: dict[str, str]
    problems: tuple[str, ...] = ()


def load_keymap(path: Path, known_ids: Callable[[], Iterable[str]]) -> LoadedKeymap:
    """The keymap in ``path`` (nothing when it does not exist). Bad entries are left out and
    named in ``problems``; a file that is not TOML gives no keys and one problem.
    ``known_ids`` is called only when there is a file: listing every binding imports the
    dialogs' screens, which the first frame does without."""
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return LoadedKeymap({})
    except OSError as error:
        return LoadedKeymap({}, (f"{path}: cannot be read ({error.strerror or error})",))
    try:
        data = loads_toml(text)
    except TomlError as error:
        return LoadedKeymap({}, (f"{path}: not TOML ({error})",))
    known = set(known_ids())
    keys: dict[str, str] = {}
    problems: list[str] = []
    for binding_id, value in _flatten(data):
        if binding_id not in known:
            problems.append(f"{path.name}: no key is named {binding_id!r}")
        elif isinstance(value, str) and value.strip():
            keys[binding_id] = ",".join(part.strip() for part in value.split(",") if part.strip())
        elif isinstance(value, list) and value and all(isinstance(v, str) and v.strip() for v in value):
            keys[binding_id] = ",".join(v.strip() for v in value)
        else:
            problems.append(f"{path.name}: {binding_id} must be a key or a list of keys, not {value!r}")
    return LoadedKeymap(keys, tuple(problems))


def _flatten(data: Mapping[str, Any], prefix: str = "") -> Iterable[tuple[str, Any]]:
    for name, value in data.items():
        if isinstance(value, dict):
            yield from _flatten(value, f"{prefix}{name}.")
        else:
            yield f"{prefix}{name}", value


# -- reading keys from bindings --------------------------------------------------------------


class KeyDisplay(Protocol):
    def get_key_display(self, binding: Binding, /) -> str: ...


def binding_keys(binding: Binding, keymap: Mapping[str, str]) -> list[str]:
    """The keys of ``binding``, the keymap's when it remaps the binding's id."""
    keys = keymap.get(binding.id, binding.key) if binding.id else binding.key
    return [key.strip() for key in keys.split(",") if key.strip()]


def key_label(binding: Binding, app: KeyDisplay, keymap: Mapping[str, str], *, first_only: bool = False) -> str:
    """How the binding's keys read on screen, as the footer writes them: ``?, f1``, ``⏎``, ``esc``
    (a key reads the same in the footer, the hints and the help)."""
    keys = binding_keys(binding, keymap)
    if first_only:
        keys = keys[:1]
    return ", ".join(app.get_key_display(Binding(key, binding.action)) for key in keys)


#: One part of a hint line: the action(s) whose keys are shown, and a few words.
Hint = tuple[str | tuple[str, ...], str]


def hint_line(app: KeyDisplay, bindings: Iterable[BindingType], hints: Sequence[Hint]) -> str:
    """``⏎ applies · esc closes · ↑/↓ history``: each action's first key, then what it does.

    Actions are named by the action or the id of their binding in ``bindings`` (a command's
    by its id: ``console.cancel_load``); one with no binding there is left out (a key is
    never written by hand)."""
    by_action: dict[str, Binding] = {}
    for binding in bindings:
        if isinstance(binding, Binding):
            by_action.setdefault(binding.action, binding)
            if binding.id:
                by_action.setdefault(binding.id, binding)
    keymap = keymap_of(app)
    parts = []
    for actions, words in hints:
        labels = [
            key_label(by_action[action], app, keymap, first_only=True)
            for action in ((actions,) if isinstance(actions, str) else actions)
            if action in by_action
        ]
        if labels:
            parts.append(f"{'/'.join(labels)} {words}")
    return " · ".join(parts)


def keymap_of(app: object) -> Mapping[str, str]:
    """The keymap the app runs with (``ConsoleApp.keymap``), or none."""
    keymap = getattr(app, "keymap", None)
    return keymap if isinstance(keymap, Mapping) else {}


def binding_ids(groups: Iterable[tuple[str, Iterable[Binding]]]) -> list[str]:
    return [binding.id for _title, bindings in groups for binding in bindings if binding.id]
