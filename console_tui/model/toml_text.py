"""TOML read from text, for the rules, keymap and fleet files: ``tomllib`` (``tomli`` on Python
3.10) is imported the first time a file is read, not at start, where it would cost the
first frame about 5 ms when no such file exists."""

from __future__ import annotations

import sys
from typing import Any


class TomlError(ValueError):
    """Text that is not TOML; the message says where and why, as the TOML reader does."""


def loads_toml(text: str) -> dict[str, Any]:
    """The table ``text`` holds; ``TomlError`` when it is not TOML. A ``RecursionError``
    (arrays or tables nested too deeply: the reader recurses) is the caller's to catch."""
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover
        import tomli as tomllib
    try:
        table: dict[str, Any] = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise TomlError(str(error)) from None
    return table
