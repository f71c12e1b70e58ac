"""A rule set: exclude and highlight entries with rqt_console's semantics.

- A row is shown when no active exclude entry matches it and (``highlighted_only`` is off
  or the row is highlighted).
- A row is highlighted when any active highlight entry matches it. While any highlight
  entry is active, shown rows that are not highlighted are dimmed. With none active, every
  row counts as highlighted (so ``highlighted_only`` alone hides nothing) and none is marked.
- An entry is active when it is enabled and its rule has input: a rule with empty input
  matches nothing, and an inverted entry matches what its rule does not match.

Rule sets are immutable values: every change returns a new set, so the previous rules stay
in force until a new set is handed to the view.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, replace
from enum import Enum
from typing import Any, Literal

from ..store.log_store import LogStore
from ..store.record import LogRecord
from .rule import Rule, RuleError

Decoration = Literal["highlight", "dim"] | None


class Role(str, Enum):
    EXCLUDE = "exclude"
    HIGHLIGHT = "highlight"


@dataclass(frozen=True)
class Entry:
    """A rule in a set: what it does (``role``), whether it is on, whether it is inverted."""

    rule: Rule
    role: Role = Role.EXCLUDE
    enabled: bool = True
    inverted: bool = False
    #: Made by the query line (replaced when the next query is applied).
    from_query: bool = False
    #: Made by a key that toggles it (``"levels"``, ``"solo"``, ``"mute"``: see ``model/rules/key_rules.py``), or "".
    toggle: str = ""

    @property
    def active(self) -> bool:
        return self.enabled and not self.rule.is_empty

    def describe(self) -> str:
        return ("not " if self.inverted else "") + self.rule.describe()


def exclude(rule: Rule, **options: Any) -> Entry:
    return Entry(rule, Role.EXCLUDE, **options)


def highlight(rule: Rule, **options: Any) -> Entry:
    return Entry(rule, Role.HIGHLIGHT, **options)


@dataclass(frozen=True)
class RuleSet:
    """Exclude and highlight entries, in the order the user made them, and the
    "highlighted only" switch."""

    entries: tuple[Entry, ...] = ()
    highlighted_only: bool = False

    # -- changes (each returns a new set) ---------------------------------------------------

    def add(self, *entries: Entry) -> RuleSet:
        return replace(self, entries=self.entries + entries)

    def replace(self, index: int, entry: Entry) -> RuleSet:
        entries = list(self.entries)
        entries[index] = entry
        return replace(self, entries=tuple(entries))

    def remove(self, index: int) -> RuleSet:
        return replace(self, entries=self.entries[:index] + self.entries[index + 1 :])

    def with_rule(self, index: int, rule: Rule) -> RuleSet:
        """Edit: the entry at ``index`` tests ``rule`` instead."""
        return self.replace(index, replace(self.entries[index], rule=rule))

    def with_enabled(self, index: int, enabled: bool) -> RuleSet:
        return self.replace(index, replace(self.entries[index], enabled=enabled))

    def with_inverted(self, index: int, inverted: bool) -> RuleSet:
        return self.replace(index, replace(self.entries[index], inverted=inverted))

    def with_role(self, index: int, role: Role) -> RuleSet:
        return self.replace(index, replace(self.entries[index], role=role))

    def with_highlighted_only(self, highlighted_only: bool) -> RuleSet:
        return replace(self, highlighted_only=highlighted_only)

    def without_rules(self, rules: set[Rule]) -> RuleSet:
        """The active entries testing any of ``rules`` switched off."""
        return replace(
            self,
            entries=tuple(replace(e, enabled=False) if e.active and e.rule in rules else e for e in self.entries),
        )

    def with_query(self, entries: tuple[Entry, ...]) -> RuleSet:
        """The entries of the previous query replaced by ``entries`` (the query line's)."""
        kept = tuple(entry for entry in self.entries if not entry.from_query)
        return replace(self, entries=kept + tuple(replace(entry, from_query=True) for entry in entries))

    def clear(self) -> RuleSet:
        return RuleSet()

    # -- questions --------------------------------------------------------------------------

    def active(self, role: Role) -> list[Entry]:
        return [entry for entry in self.entries if entry.active and entry.role is role]

    @property
    def highlighting(self) -> bool:
        """Some highlight entry is active (rows not highlighted are dimmed)."""
        return any(entry.active and entry.role is Role.HIGHLIGHT for entry in self.entries)

    @property
    def filtering(self) -> bool:
        """Some rows may be hidden."""
        return bool(self.active(Role.EXCLUDE)) or (self.highlighted_only and self.highlighting)

    def active_rules(self) -> list[Rule]:
        """The distinct rules of the active entries (each is tested once per record)."""
        return list(dict.fromkeys(entry.rule for entry in self.entries if entry.active))

    # -- the semantics ----------------------------------------------------------------------

    def decide(self, masks: Mapping[Rule, bytes], size: int) -> tuple[bytes, bytes]:
        """Given each active rule's match mask over ``size`` records: (shown, highlighted) masks."""
        ones = int.from_bytes(b"\x01" * size, "little")
        as_int: dict[Rule, int] = {}

        def matched(entry: Entry) -> int:
            found = as_int.get(entry.rule)
            if found is None:
                found = as_int[entry.rule] = int.from_bytes(masks[entry.rule], "little")
            return found ^ ones if entry.inverted else found

        excluded = 0
        for entry in self.active(Role.EXCLUDE):
            excluded |= matched(entry)
        highlights = self.active(Role.HIGHLIGHT)
        highlighted = ones
        if highlights:
            highlighted = 0
            for entry in highlights:
                highlighted |= matched(entry)
        shown = excluded ^ ones
        if self.highlighted_only:
            shown &= highlighted
        return shown.to_bytes(size, "little"), highlighted.to_bytes(size, "little")

    def verdict(self, record: LogRecord) -> tuple[bool, Decoration]:
        """Whether one record is shown, and how it is marked (for tests and previews)."""
        store = LogStore(1)
        store.append(record)
        span = next(store.spans(0, 1))
        masks = {rule: rule.compile(store)(span.chunk, 0, 1) for rule in self.active_rules()}
        shown, highlighted = self.decide(masks, 1)
        decoration: Decoration = None
        if self.highlighting:
            decoration = "highlight" if highlighted == b"\x01" else "dim"
        return shown == b"\x01", decoration

    # -- plain values (rules files) ---------------------------------------------------------

    def to_dict(self) -> dict[str, Any]:
        return {
            "highlighted_only": self.highlighted_only,
            "rules": [
                {"role": e.role.value, "enabled": e.enabled, "inverted": e.inverted, **e.rule.to_dict()}
                for e in self.entries
            ],
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> RuleSet:
        """``RuleError`` naming the first bad key (``rules[2].levels: ...``)."""
        unknown = sorted(set(data) - {"highlighted_only", "rules"})
        if unknown:
            raise RuleError(f"unknown key {unknown[0]!r} (expected 'highlighted_only' or 'rules')")
        highlighted_only = data.get("highlighted_only", False)
        if not isinstance(highlighted_only, bool):
            raise RuleError("highlighted_only: expected true or false")
        rules = data.get("rules", [])
        if not isinstance(rules, list):
            raise RuleError("rules: expected an array of tables ([[rules]])")
        return cls(tuple(_entry_from_dict(item, f"rules[{i}]") for i, item in enumerate(rules)), highlighted_only)


_ENTRY_KEYS = ("role", "enabled", "inverted")


def _entry_from_dict(item: Any, where: str) -> Entry:
    if not isinstance(item, Mapping):
        raise RuleError(f"{where}: expected a table")
    role_name = item.get("role", "exclude")
    try:
        role = Role(role_name)
    except ValueError:
        raise RuleError(f"{where}.role: expected 'exclude' or 'highlight', got {role_name!r}") from None
    flags = {}
    for key in ("enabled", "inverted"):
        value = item.get(key, key == "enabled")
        if not isinstance(value, bool):
            raise RuleError(f"{where}.{key}: expected true or false, got {value!r}")
        flags[key] = value
    rule = rule_from_dict({k: v for k, v in item.items() if k not in _ENTRY_KEYS}, where)
    return Entry(rule, role, enabled=flags["enabled"], inverted=flags["inverted"])


def rule_from_dict(item: Any, where: str) -> Rule:
    """A rule from plain values (``kind`` and its fields); ``RuleError`` prefixed with ``where``."""
    if not isinstance(item, Mapping):
        raise RuleError(f"{where}: expected a table")
    kind = item.get("kind")
    cls = Rule.kinds.get(kind) if isinstance(kind, str) else None
    if cls is None:
        raise RuleError(f"{where}.kind: expected one of {', '.join(sorted(Rule.kinds))}, got {kind!r}")
    fields = {k: v for k, v in item.items() if k != "kind"}
    known = set(cls.__dataclass_fields__)
    unknown = sorted(set(fields) - known)
    if unknown:
        raise RuleError(f"{where}.{unknown[0]}: not a field of a {kind} rule ({', '.join(sorted(known))})")
    try:
        return cls.from_fields(fields)
    except RuleError as error:
        joiner = "." if _FIELD_PREFIX.match(error.message) else ": "
        raise RuleError(f"{where}{joiner}{error.message}", error.position) from None


_FIELD_PREFIX = re.compile(r"[a-z_]+(\[\d+\])?[.:]")
