"""One-key toggles: severity levels, nodes (solo / mute), and what the Time column shows.

Level and node toggles are rules (``model/rules/key_rules.py``): applied like any rule, shown in the
rules pane, in the status line.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from ...model.loggers.logger_levels import robot_qualified
from ...model.rules import key_rules as toggles
from ...model.rules.ruleset import RuleSet
from ...model.time_column import TimeFormat, format_info, next_format, sim_time_note
from ..widgets.node_pane import NodePane
from .context import ConsoleContext


class TogglesController:
    """Levels, nodes and time formats in one key each."""

    def __init__(
        self,
        context: ConsoleContext,
        node_pane: NodePane,
        *,
        rules: Callable[[], RuleSet],
        apply_rules: Callable[[RuleSet], None],
        live: Callable[[], bool],
    ) -> None:
        self._store, self._table, self._changed = context.store, context.table, context.changed
        self._node_pane = node_pane
        #: The rules in force, and how to put others in force.
        self._rules = rules
        self._apply_rules = apply_rules
        #: Whether live sources run (a sim time note is about them).
        self._live = live

    # -- levels -----------------------------------------------------------------------------------

    def toggle_level(self, level: int) -> None:
        self._apply_rules(toggles.toggle_level(self._rules(), level))

    def raise_minimum(self) -> None:
        self._apply_rules(toggles.raise_minimum(self._rules()))

    def lower_minimum(self) -> None:
        self._apply_rules(toggles.lower_minimum(self._rules()))

    def all_levels(self) -> None:
        self._apply_rules(toggles.with_hidden_levels(self._rules(), frozenset()))

    def minimum_level(self, level: int) -> None:
        self._apply_rules(toggles.with_minimum(self._rules(), level))

    # -- nodes ------------------------------------------------------------------------------------

    def node_toggles(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        """The nodes soloed and muted (the node panel marks them)."""
        rules = self._rules()
        return toggles.soloed(rules), toggles.muted(rules)

    def node_panel_toggle(self, message: NodePane.Toggle) -> None:
        rules = self._rules()
        if message.kind == "solo":
            self._apply_rules(toggles.toggle_solo(rules, message.node))
        elif message.kind == "mute":
            self._apply_rules(toggles.toggle_mute(rules, message.node))
        else:
            self._apply_rules(toggles.without_node_toggles(rules))
        self._node_pane.show()

    def _row_node(self) -> str | None:
        """The cursor row's node as solo and mute name it (in a fleet, that robot's node)."""
        seq = self._table.cursor_seq
        if seq is None or seq not in self._store:
            return None
        record = self._store.get(seq)
        return robot_qualified(record.robot, record.node)

    def solo_row_node(self) -> None:
        node = self._row_node()
        if node is not None:
            self._apply_rules(toggles.toggle_solo(self._rules(), node))

    def mute_row_node(self) -> None:
        node = self._row_node()
        if node is not None:
            self._apply_rules(toggles.toggle_mute(self._rules(), node))

    def clear_node_toggles(self) -> None:
        self._apply_rules(toggles.without_node_toggles(self._rules()))

    def status(self) -> str:
        """``level≥WARN · solo navigation.planner``: the toggles in force, for the status line."""
        rules = self._rules()
        return " · ".join(part for part in (toggles.levels_text(rules), toggles.nodes_text(rules)) if part)

    # -- time -------------------------------------------------------------------------------------

    def next_time_format(self) -> None:
        self.time_format(next_format(self._table.time_format).value)

    def time_format(self, name: str) -> None:
        self._table.set_time_format(TimeFormat(name), self._table.utc)
        self._changed()

    def toggle_utc(self) -> None:
        self._table.set_time_format(self._table.time_format, not self._table.utc)
        self._changed()

    def time_status(self) -> str:
        """What the Time column shows when not the local wall clock, and a sim time note."""
        table = self._table
        fmt = table.time_format
        parts = []
        if fmt is not TimeFormat.CLOCK:
            parts.append(f"time: {format_info(fmt).name}")
        store = self._store
        if len(store):
            now = time.time_ns()
            newest = store.get(store.end_seq - 1).stamp_ns
            note = sim_time_note(newest, now, live=self._live())
            if note:
                parts.append(note)
        return ", ".join(parts)
