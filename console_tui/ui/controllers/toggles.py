"""One-key toggles: severity levels, nodes (solo / mute), and what the Time column shows.

Level and node toggles are rules (``model/rules/key_rules.py``): applied like any rule, shown in the
rules pane, in the status line.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import ClassVar

from ...model.levels import MESSAGE_SEVERITIES
from ...model.loggers.logger_levels import robot_qualified
from ...model.rules import key_rules as toggles
from ...model.rules.ruleset import RuleSet
from ...model.time_column import FORMATS, TimeFormat, format_info, next_format, sim_time_note
from ..command_table import NAVIGATION, Command
from ..widgets.node_pane import NodePane
from .context import ConsoleContext


def _toggling_level(level: int) -> Callable[[TogglesController], None]:
    return lambda toggles: toggles.toggle_level(level)


def _minimum(level: int) -> Callable[[TogglesController], None]:
    return lambda toggles: toggles.minimum_level(level)


def _showing_time(fmt: TimeFormat) -> Callable[[TogglesController], None]:
    return lambda toggles: toggles.time_format(fmt.value)


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
        self.time_format(next_format(self._table.painter.time_format).value)

    def time_format(self, name: str) -> None:
        self._table.set_time_format(TimeFormat(name), self._table.painter.utc)
        self._changed()

    def toggle_utc(self) -> None:
        painter = self._table.painter
        self._table.set_time_format(painter.time_format, not painter.utc)
        self._changed()

    def time_status(self) -> str:
        """What the Time column shows when not the local wall clock, and a sim time note."""
        table = self._table
        fmt = table.painter.time_format
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

    COMMANDS: ClassVar[tuple[Command[TogglesController], ...]] = (
        *(
            Command(
                f"levels.{severity.name.lower()}",
                _toggling_level(int(severity)),
                str(number),
                f"Show / hide {severity.name} messages",
                group=NAVIGATION,
                title=f"Show / hide {severity.name}",
                about=f"Hide {severity.name} messages, or show them again (a rule underneath)",
            )
            for number, severity in enumerate(MESSAGE_SEVERITIES, start=1)
        ),
        *(
            Command(
                f"levels.minimum_{severity.name.lower()}",
                _minimum(int(severity)),
                title=f"Minimum level: {severity.name}",
                about=f"Show {severity.name} and worse",
            )
            for severity in MESSAGE_SEVERITIES
        ),
        Command(
            "levels.up",
            raise_minimum,
            "greater_than_sign",
            "Minimum level up (hide the lowest shown)",
            group=NAVIGATION,
            title="Minimum level up",
            about="Hide the lowest level shown",
        ),
        Command(
            "levels.down",
            lower_minimum,
            "less_than_sign",
            "Minimum level down (show one more)",
            group=NAVIGATION,
            title="Minimum level down",
            about="Show one more level",
        ),
        Command(
            "levels.all",
            all_levels,
            "0",
            "Every level shown again",
            group=NAVIGATION,
            title="Every level",
            about="Show every level again",
            words="severity level",
        ),
        Command(
            "nav.solo_row_node",
            solo_row_node,
            title="Solo this row's node",
            about="Show only the selected row's node (again: undo)",
        ),
        Command(
            "nav.mute_row_node",
            mute_row_node,
            title="Mute this row's node",
            about="Hide the selected row's node (again: undo)",
        ),
        Command("nav.every_node", clear_node_toggles, title="Every node heard", about="No node soloed or muted"),
        *(
            Command(
                f"time.{fmt.value}",
                _showing_time(fmt),
                title=f"Time: {format_info(fmt).name}",
                about=f"The Time column shows the {format_info(fmt).name}",
            )
            for fmt in FORMATS
        ),
        Command(
            "time.format",
            next_time_format,
            "t",
            "Time format: clock, date, stamp, since first, since row, Δ",
            group=NAVIGATION,
            title="Time format: the next one",
            about="Wall clock, date, stamp, since first, since row, delta",
        ),
        Command(
            "time.utc",
            toggle_utc,
            "ctrl+u",
            "Time in UTC / local time",
            group=NAVIGATION,
            about="The wall clock in UTC, or local time",
        ),
    )
