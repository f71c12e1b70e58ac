"""Level and node toggles: rules made and changed by one key.

They are ordinary entries of the rule set, tagged by the toggle that owns them
(``Entry.toggle``), so they compose with every other rule, show in the rules pane and can be
switched off, edited or deleted there like any rule:

- ``levels``: exclude the hidden severities (``SeverityRule``): a minimum level hides those
  below it, and each level can be hidden or shown on its own;
- ``solo``: exclude, inverted, the soloed nodes (``NodeRule``): only they are shown;
- ``mute``: exclude the muted nodes.

Node names are matched exactly: characters a glob would read (``*?[``) are quoted.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ..levels import MESSAGE_SEVERITIES, severity_name
from .node import NodeRule
from .ruleset import Entry, Role, RuleSet
from .severity import SeverityRule

LEVELS, SOLO, MUTE = "levels", "solo", "mute"
ALL_LEVELS: frozenset[int] = frozenset(int(s) for s in MESSAGE_SEVERITIES)
_ORDER = [int(s) for s in MESSAGE_SEVERITIES]


def toggle_entry(rules: RuleSet, name: str) -> Entry | None:
    return next((entry for entry in rules.entries if entry.toggle == name), None)


def with_toggle(rules: RuleSet, name: str, entry: Entry | None) -> RuleSet:
    """``rules`` with the toggle's entry replaced by ``entry`` (in its place), added, or
    removed (``None``)."""
    for index, old in enumerate(rules.entries):
        if old.toggle == name:
            return rules.remove(index) if entry is None else rules.replace(index, entry)
    return rules if entry is None else rules.add(entry)


# -- levels -----------------------------------------------------------------------------------


def hidden_levels(rules: RuleSet) -> frozenset[int]:
    """The severities the level toggles hide now (none while their rule is switched off)."""
    entry = toggle_entry(rules, LEVELS)
    if entry is None or not entry.enabled or entry.role is not Role.EXCLUDE:
        return frozenset()
    if not isinstance(entry.rule, SeverityRule):
        return frozenset()
    levels = entry.rule.levels
    return ALL_LEVELS - levels if entry.inverted else levels


def with_hidden_levels(rules: RuleSet, hidden: frozenset[int]) -> RuleSet:
    entry = Entry(SeverityRule(hidden), Role.EXCLUDE, toggle=LEVELS) if hidden else None
    return with_toggle(rules, LEVELS, entry)


def toggle_level(rules: RuleSet, level: int) -> RuleSet:
    """Hide ``level`` if shown, show it if hidden."""
    return with_hidden_levels(rules, hidden_levels(rules) ^ {int(level)})


def minimum_level(rules: RuleSet) -> int:
    """The lowest severity shown (DEBUG when all are; above FATAL when none is)."""
    hidden = hidden_levels(rules)
    return next((level for level in _ORDER if level not in hidden), _ORDER[-1] + 10)


def with_minimum(rules: RuleSet, level: int) -> RuleSet:
    """Show ``level`` and every level above it, hide those below."""
    return with_hidden_levels(rules, frozenset(lv for lv in _ORDER if lv < level))


def raise_minimum(rules: RuleSet) -> RuleSet:
    """Hide the lowest level shown, and those below it (never FATAL); the levels hidden on
    their own above it stay hidden."""
    hidden = hidden_levels(rules)
    lowest = minimum_level(rules)
    above = [level for level in _ORDER if level > lowest and level not in hidden]
    if not above:
        return rules
    return with_hidden_levels(rules, hidden | {level for level in _ORDER if level < above[0]})


def lower_minimum(rules: RuleSet) -> RuleSet:
    """Show the level just below the lowest shown (the levels hidden on their own above it
    stay hidden)."""
    hidden = hidden_levels(rules)
    below = [level for level in _ORDER if level < minimum_level(rules)]
    return with_hidden_levels(rules, hidden - {below[-1]}) if below else rules


def levels_text(rules: RuleSet) -> str:
    """The status line's words: ``""`` (every level), ``level≥WARN``, ``hiding INFO, ERROR``,
    ``level≥INFO, hiding ERROR``."""
    hidden = hidden_levels(rules)
    if not hidden:
        return ""
    if hidden == ALL_LEVELS:
        return "every level hidden"
    lowest = minimum_level(rules)
    others = [severity_name(level) for level in _ORDER if level in hidden and level > lowest]
    if lowest == _ORDER[0]:
        return "hiding " + ", ".join(others)
    minimum = f"level≥{severity_name(lowest)}"
    return f"{minimum}, hiding {', '.join(others)}" if others else minimum


# -- nodes ------------------------------------------------------------------------------------

_GLOB = re.compile(r"([*?[])")
_QUOTED = re.compile(r"\[([*?[])\]")


def exact_name(name: str) -> str:
    """A node name as a ``NodeRule`` name that matches only it (glob characters quoted)."""
    return _GLOB.sub(r"[\1]", name)


def plain_name(name: str) -> str:
    """The inverse of ``exact_name``."""
    return _QUOTED.sub(r"\1", name)


def _names(rules: RuleSet, toggle: str) -> tuple[str, ...]:
    entry = toggle_entry(rules, toggle)
    if entry is None or not entry.enabled or not isinstance(entry.rule, NodeRule):
        return ()
    return tuple(plain_name(name) for name in entry.rule.names)


def soloed(rules: RuleSet) -> tuple[str, ...]:
    """The nodes soloed: only they are shown (when any is)."""
    return _names(rules, SOLO)


def muted(rules: RuleSet) -> tuple[str, ...]:
    """The nodes muted: hidden."""
    return _names(rules, MUTE)


def _with_names(rules: RuleSet, toggle: str, names: tuple[str, ...]) -> RuleSet:
    if not names:
        return with_toggle(rules, toggle, None)
    rule = NodeRule(tuple(exact_name(name) for name in names))
    entry = toggle_entry(rules, toggle)
    if entry is not None:
        return with_toggle(rules, toggle, replace(entry, rule=rule, enabled=True))
    return with_toggle(rules, toggle, Entry(rule, Role.EXCLUDE, inverted=toggle == SOLO, toggle=toggle))


def toggle_solo(rules: RuleSet, node: str) -> RuleSet:
    """Solo ``node`` (with the nodes soloed already), or take it out of the solo."""
    return _toggle_node(rules, node, SOLO, MUTE)


def toggle_mute(rules: RuleSet, node: str) -> RuleSet:
    """Mute ``node``, or hear it again."""
    return _toggle_node(rules, node, MUTE, SOLO)


def _toggle_node(rules: RuleSet, node: str, toggle: str, other: str) -> RuleSet:
    """``node`` out of ``toggle``'s names if it is in them, else into them and out of ``other``'s."""
    names = _names(rules, toggle)
    if node in names:
        return _with_names(rules, toggle, tuple(n for n in names if n != node))
    rules = _with_names(rules, other, tuple(n for n in _names(rules, other) if n != node))
    return _with_names(rules, toggle, (*names, node))


def without_node_toggles(rules: RuleSet) -> RuleSet:
    """No node soloed or muted any more."""
    return with_toggle(with_toggle(rules, SOLO, None), MUTE, None)


def nodes_text(rules: RuleSet) -> str:
    """The status line's words: ``solo navigation.planner``, ``muted 3 nodes``..."""
    parts = []
    for word, names in (("solo", soloed(rules)), ("muted", muted(rules))):
        if len(names) == 1:
            parts.append(f"{word} {names[0]}")
        elif names:
            parts.append(f"{word} {len(names)} nodes")
    return ", ".join(parts)
