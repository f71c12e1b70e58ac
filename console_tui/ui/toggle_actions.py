"""The app's one-key toggles: severity levels, nodes (solo / mute, the node panel), and what
the Time column shows.

A part of ``ConsoleApp`` (it mixes this in). Level and node toggles are rules
(``model/toggles.py``): applied like any rule, shown in the rules pane, in the status line.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from ..model import toggles
from ..model.logger_levels import robot_qualified
from ..model.rules.ruleset import RuleSet
from ..model.time_column import TimeFormat, format_info, next_format, sim_time_note
from .app_part import AppPart
from .widgets.logger_pane import LoggerPane
from .widgets.node_pane import NodePane


class ToggleActions(AppPart):
    """Levels, nodes and time formats in one key each."""

    # What it uses of the app (``ConsoleApp`` sets them).
    node_pane: NodePane
    logger_pane: LoggerPane
    rules: RuleSet
    apply_rules: Callable[[RuleSet], None]
    #: The live sources (none when only files are shown).
    sources: list

    # -- levels -----------------------------------------------------------------------------------

    def action_toggle_level(self, level: int) -> None:
        self.apply_rules(toggles.toggle_level(self.rules, level))

    def action_raise_minimum(self) -> None:
        self.apply_rules(toggles.raise_minimum(self.rules))

    def action_lower_minimum(self) -> None:
        self.apply_rules(toggles.lower_minimum(self.rules))

    def action_all_levels(self) -> None:
        self.apply_rules(toggles.with_hidden_levels(self.rules, frozenset()))

    def action_minimum_level(self, level: int) -> None:
        self.apply_rules(toggles.with_minimum(self.rules, level))

    # -- nodes ------------------------------------------------------------------------------------

    def node_toggles(self) -> tuple[tuple[str, ...], tuple[str, ...]]:
        return toggles.soloed(self.rules), toggles.muted(self.rules)

    def action_toggle_nodes(self) -> None:
        if not self.node_pane.is_open:
            self.logger_pane.close()  # the two share the right side
        self.node_pane.toggle()

    def on_node_pane_toggle(self, message: NodePane.Toggle) -> None:
        if message.kind == "solo":
            self.apply_rules(toggles.toggle_solo(self.rules, message.node))
        elif message.kind == "mute":
            self.apply_rules(toggles.toggle_mute(self.rules, message.node))
        else:
            self.apply_rules(toggles.without_node_toggles(self.rules))
        self.node_pane.show()

    def _row_node(self) -> str | None:
        """The cursor row's node as solo and mute name it (in a fleet, that robot's node)."""
        seq = self.table.cursor_seq
        if seq is None or seq not in self.store:
            return None
        record = self.store.get(seq)
        return robot_qualified(record.robot, record.node)

    def action_solo_row_node(self) -> None:
        node = self._row_node()
        if node is not None:
            self.apply_rules(toggles.toggle_solo(self.rules, node))

    def action_mute_row_node(self) -> None:
        node = self._row_node()
        if node is not None:
            self.apply_rules(toggles.toggle_mute(self.rules, node))

    def action_clear_node_toggles(self) -> None:
        self.apply_rules(toggles.without_node_toggles(self.rules))

    def toggles_status(self) -> str:
        """``level≥WARN · solo navigation.planner``: the toggles in force, for the status line."""
        return " · ".join(part for part in (toggles.levels_text(self.rules), toggles.nodes_text(self.rules)) if part)

    # -- time -------------------------------------------------------------------------------------

    def action_next_time_format(self) -> None:
        self.action_time_format(next_format(self.table.time_format).value)

    def action_time_format(self, name: str) -> None:
        self.table.set_time_format(TimeFormat(name), self.table.utc)
        self.update_status()

    def action_toggle_utc(self) -> None:
        self.table.set_time_format(self.table.time_format, not self.table.utc)
        self.update_status()

    def time_status(self) -> str:
        """What the Time column shows when not the local wall clock, and a sim time note."""
        table = self.table
        fmt = table.time_format
        parts = []
        if fmt is not TimeFormat.CLOCK:
            parts.append(f"time: {format_info(fmt).name}")
        store = self.store
        if len(store):
            now = time.time_ns()
            newest = store.get(store.end_seq - 1).stamp_ns
            note = sim_time_note(newest, now, live=bool(self.sources))
            if note:
                parts.append(note)
        return ", ".join(parts)
