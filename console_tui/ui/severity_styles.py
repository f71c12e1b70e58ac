"""How a severity is drawn, in every widget that shows one: CSS from the theme, written once.

Each widget names its component classes after the severity table (``model.levels``):
``log-table--severity-warn``, ``status-bar--severity-error``... and takes its rules from
``severity_css``. A severity reads at a glance in every mode, by its word and its weight, not
only its hue: DEBUG muted (dim without colour), INFO plain, WARN bold, ERROR bold (underlined without colour),
FATAL bold on the error colour (reversed without colour). The colours are the theme's, picked
so that a 16-colour terminal still draws WARN yellow and ERROR red; under ``NO_COLOR``
(Textual's ``:nocolor``, which turns colours grey by their brightness) the weights carry it,
so that ERROR is never drawn darker than INFO.
"""

from __future__ import annotations

from ..model.levels import SEVERITY_TABLE

#: The word of a severity, by style name: colour, then text style.
_CELL = {
    "debug": "color: $foreground-muted;",
    "info": "color: $text-success;",
    "warn": "color: $text-warning; text-style: bold;",
    "error": "color: $error; text-style: bold;",
    "fatal": "background: $error; color: $text; text-style: bold;",
}
_CELL_NO_COLOR = {
    "debug": "color: $foreground-muted; text-style: dim;",
    "info": "color: $foreground;",
    "warn": "color: $foreground; text-style: bold;",
    "error": "color: $foreground; text-style: bold underline;",
    "fatal": "background: $background; color: $foreground; text-style: bold reverse;",
}

#: A whole row of that severity (the table's other cells): quieter than the word.
_ROW = {
    "debug": "color: $foreground-muted;",
    "info": "",
    "warn": "color: $text-warning;",
    "error": "color: $text-error;",
    "fatal": "color: $text-error; text-style: bold;",
}
_ROW_NO_COLOR = {
    "debug": "color: $foreground-muted; text-style: dim;",
    "info": "",
    "warn": "color: $foreground;",
    "error": "color: $foreground;",
    "fatal": "color: $foreground; text-style: bold;",
}


def severity_classes(prefix: str) -> set[str]:
    """The component classes ``prefix-debug`` ... ``prefix-fatal``."""
    return {f"{prefix}-{level.style}" for level in SEVERITY_TABLE}


def severity_css(widget: str, prefix: str, *, row: bool = False) -> str:
    """CSS for the component classes ``prefix-<style>`` of ``widget``: the severity's word,
    or with ``row`` a whole row of it."""
    looks, plain_looks = (_ROW, _ROW_NO_COLOR) if row else (_CELL, _CELL_NO_COLOR)
    rules = []
    for level in SEVERITY_TABLE:
        name = f"{prefix}-{level.style}"
        rules.append(f"{widget} > .{name} {{ {looks[level.style]} }}")
        rules.append(f"{widget}:nocolor > .{name} {{ {plain_looks[level.style]} }}")
    return "\n".join(rules)
