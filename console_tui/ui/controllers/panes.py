"""The side panes beside the table: the logger levels pane and the node panel (they share the
right side), and the logger pane's temporary levels. (The rules pane is the rules controller's.)"""

from __future__ import annotations

from typing import ClassVar

from ...model.loggers.logger_pane_state import shown_logger
from ..command_table import Command
from ..screens.temporary_level import TemporaryLevelScreen
from ..widgets.logger_pane import LoggerPane
from ..widgets.node_pane import NodePane
from .context import ConsoleContext

#: How long ``t`` sets a temporary level for unless told otherwise.
DEFAULT_TEMPORARY_S = 30.0


class PanesController:
    """Opening the logger levels pane and the node panel, and a temporary level's dialog."""

    def __init__(self, context: ConsoleContext, logger_pane: LoggerPane, node_pane: NodePane) -> None:
        self._host, self._store, self._table = context.host, context.store, context.table
        self._logger_pane = logger_pane
        self._node_pane = node_pane

    def toggle_loggers(self) -> None:
        if not self._logger_pane.is_open:
            self._node_pane.close()  # the two share the right side
        self._logger_pane.toggle()

    def toggle_nodes(self) -> None:
        if not self._node_pane.is_open:
            self._logger_pane.close()
        self._node_pane.toggle()

    def loggers_for_row(self) -> None:
        """Open the logger levels pane on the node of the table's selected row."""
        self._node_pane.close()
        seq = self._table.cursor_seq
        if seq is None or seq not in self._store:
            self._logger_pane.open()
        else:
            record = self._store.get(seq)
            self._logger_pane.open_for_logger(record.node, record.robot)

    def ask_temporary_level(self, message: LoggerPane.TemporaryRequested) -> None:
        """Ask which level and for how long, then have the pane set it."""
        pane, fqn, logger = message.pane, message.fqn, message.logger

        def chosen(choice: tuple[int, float] | None) -> None:
            if choice is not None:
                pane.set_temporary(fqn, logger, *choice)

        self._host.push_screen(TemporaryLevelScreen(fqn, shown_logger(logger), DEFAULT_TEMPORARY_S), chosen)

    COMMANDS: ClassVar[tuple[Command[PanesController], ...]] = (
        Command(
            "console.loggers",
            toggle_loggers,
            "l",
            "Loggers",
            footer=100,
            title="Logger levels",
            about="Show or hide the logger levels pane",
        ),
        Command(
            "console.nodes",
            toggle_nodes,
            "ctrl+n",
            "Nodes",
            footer=110,
            about="The node panel: every node, its counts and rate; solo, mute",
        ),
        Command(
            "console.loggers_for_row",
            loggers_for_row,
            "L",
            "Logger levels of the row's node",
            title="Logger levels of this row's node",
            about="Open the logger levels pane on the selected row's node",
        ),
    )
