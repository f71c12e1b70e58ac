"""The app's side panes beside the table (the logger levels pane; the rules pane is in
``rule_actions``, the node panel in ``toggle_actions``): opening them, and what their messages
ask of the app.

A part of ``ConsoleApp`` (it mixes this in).
"""

from __future__ import annotations

from ..model.logger_view import shown_logger
from .app_part import AppPart
from .focus import focus_now
from .screens.temporary_level import TemporaryLevelScreen
from .widgets.logger_pane import LoggerPane
from .widgets.node_pane import NodePane
from .widgets.side_pane import SidePane

#: How long ``t`` sets a temporary level for unless told otherwise.
DEFAULT_TEMPORARY_S = 30.0


class PaneActions(AppPart):
    """The keys that open the logger levels pane, its temporary levels, and the table taking
    the focus back from any pane."""

    # What it uses of the app (``ConsoleApp`` sets them).
    logger_pane: LoggerPane
    node_pane: NodePane

    def action_toggle_loggers(self) -> None:
        if not self.logger_pane.is_open:
            self.node_pane.close()  # the two share the right side
        self.logger_pane.toggle()

    def action_loggers_for_row(self) -> None:
        """Open the logger levels pane on the node of the table's selected row."""
        self.node_pane.close()
        seq = self.table.cursor_seq
        if seq is None or seq not in self.store:
            self.logger_pane.open()
        else:
            record = self.store.get(seq)
            self.logger_pane.open_for_logger(record.node, record.robot)

    def on_logger_pane_temporary_requested(self, message: LoggerPane.TemporaryRequested) -> None:
        """Ask which level and for how long, then have the pane set it."""
        pane, fqn, logger = message.pane, message.fqn, message.logger

        def chosen(choice: tuple[int, float] | None) -> None:
            if choice is not None:
                pane.set_temporary(fqn, logger, *choice)

        self.push_screen(TemporaryLevelScreen(fqn, shown_logger(logger), DEFAULT_TEMPORARY_S), chosen)

    def on_side_pane_leave(self, _message: SidePane.Leave) -> None:
        focus_now(self.table)
