"""Rule sets in TOML files, and where the last rule set and the query history are kept.

    highlighted_only = false

    [[rules]]
    role = "exclude"        # or "highlight"
    enabled = true
    inverted = false
    kind = "severity"       # message, severity, node, robot, location, time, custom
    levels = ["debug"]

    [[rules]]
    role = "highlight"
    kind = "custom"
    [[rules.parts]]
    kind = "node"
    names = ["nav*"]

Reading uses ``tomllib`` (``toml_text``); writing is the small writer below (the values are only text,
booleans, whole numbers, lists of text and nested rule tables).
"""

from __future__ import annotations

import os
import shutil
import stat
from pathlib import Path
from typing import Any

import platformdirs

from ..atomic_file import atomic_output
from ..timefmt import full_text
from ..toml_text import TomlError, loads_toml
from .rule import RuleError
from .ruleset import RuleSet

APP_DIR = "console-tui"


class RulesFileError(RuleError):
    """A rules file that cannot be read: the message names the file and the problem."""


def config_dir() -> Path:
    """``$XDG_CONFIG_HOME/console-tui``, by default ``~/.config/console-tui``."""
    base = os.environ.get("XDG_CONFIG_HOME") or ""
    root = Path(base) if os.path.isabs(base) else Path.home() / ".config"
    return root / APP_DIR


def state_dir() -> Path:
    """Where what a session leaves for the next one is kept: ``$XDG_STATE_HOME/console-tui``,
    by default ``~/.local/state/console-tui`` (platformdirs' user state directory; a
    relative ``$XDG_STATE_HOME`` is ignored, as the XDG specification says)."""
    path = Path(platformdirs.user_state_dir(APP_DIR, appauthor=False))
    return path if path.is_absolute() else Path.home() / ".local" / "state" / APP_DIR


def last_rules_path() -> Path:
    """Where the rule set in use is saved on exit, to be restored at the next start."""
    return _state_file("last-rules.toml")


def query_history_path() -> Path:
    return _state_file("query-history.txt")


def _state_file(name: str) -> Path:
    """``state_dir() / name``; a file of that name left in the configuration directory by an
    older console-tui moves there the first time (only a regular file of this user's)."""
    path = state_dir() / name
    old = config_dir() / name
    if path.exists() or path.is_symlink():
        return path
    try:
        info = old.lstat()
    except OSError:
        return path
    if not stat.S_ISREG(info.st_mode) or info.st_uid != os.getuid():
        return path
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        shutil.move(old, path)
    except OSError:
        return old  # no state directory to be had: read and write it where it is
    return path


def loads_rules(text: str, name: str = "rules") -> RuleSet:
    try:
        data = loads_toml(text)
    except TomlError as error:
        raise RulesFileError(f"{name}: not valid TOML: {error}") from None
    except RecursionError:  # tomllib reads nested arrays and tables recursively
        raise RulesFileError(f"{name}: not a rules file: arrays or tables nested too deeply") from None
    try:
        return RuleSet.from_dict(data)
    except RuleError as error:
        raise RulesFileError(f"{name}: {error.message}", error.position) from None
    except RecursionError:
        raise RulesFileError(f"{name}: not a rules file: values nested too deeply") from None


def load_rules(path: str | os.PathLike[str]) -> RuleSet:
    """Read a rule set; ``RulesFileError`` naming the file and the line or key at fault."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise RulesFileError(f"{path}: cannot read: {getattr(error, 'strerror', None) or error}") from None
    return loads_rules(text, str(path))


def dumps_rules(rules: RuleSet) -> str:
    data = rules.to_dict()
    lines = ["# console-tui rule set", f"highlighted_only = {_toml_value(data['highlighted_only'])}"]
    for rule in data["rules"]:
        lines.append("")
        _toml_table(lines, "rules", rule)
    return "\n".join(lines) + "\n"


def save_rules(rules: RuleSet, path: str | os.PathLike[str]) -> None:
    """Write atomically (a crash never leaves half a file); ``OSError`` if it cannot."""
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    with atomic_output(target) as stream:
        stream.write(dumps_rules(rules).encode("utf-8"))


def _toml_table(lines: list[str], name: str, fields: dict[str, Any]) -> None:
    lines.append(f"[[{name}]]")
    nested = []
    for key, value in fields.items():
        if isinstance(value, list) and value and isinstance(value[0], dict):
            nested.append((key, value))
            continue
        comment = f"  # {full_text(value, utc=True)}" if key.endswith("_ns") else ""
        lines.append(f"{key} = {_toml_value(value)}{comment}")
    for key, tables in nested:
        for table in tables:
            _toml_table(lines, f"{name}.{key}", table)


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(item) for item in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} to a rules file")


def _toml_string(text: str) -> str:
    out = ['"']
    for ch in text:
        code = ord(ch)
        if ch in '"\\':
            out.append("\\" + ch)
        elif code < 0x20 or code == 0x7F:
            out.append({"\n": "\\n", "\t": "\\t", "\r": "\\r"}.get(ch, f"\\u{code:04X}"))
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)
