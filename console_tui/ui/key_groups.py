"""Every key of the app by where it works: the table's, the commands' (``command_table``, in
their groups), then each pane's, line's and dialog's own. The help screen lists them, the
keymap knows their ids, the palette shows the keys of its entries from them."""

from __future__ import annotations

from collections.abc import Iterable

from textual.binding import Binding, BindingType

from .command_table import CommandTable
from .widgets.log_table import LogTable
from .widgets.logger_pane import LoggerPane
from .widgets.node_pane import NodePane
from .widgets.query_bar import QueryBar
from .widgets.rules_pane import RulesPane
from .widgets.search_bar import SearchBar
from .widgets.timeline_strip import TimelineStrip


def bindings_of(bindings: Iterable[BindingType]) -> list[Binding]:
    return [binding for binding in bindings if isinstance(binding, Binding)]


def key_groups(commands: CommandTable) -> list[tuple[str, list[Binding]]]:
    """Every key, by where it works."""
    # The dialogs' screens load when first needed, not with the first frame (keys.load_keymap).
    from .screens.detail import DetailScreen
    from .screens.mark_list import MarksScreen
    from .screens.summary import SummaryScreen

    return [
        ("Table", bindings_of(LogTable.BINDINGS)),
        *commands.help_groups(),
        ("Search line", bindings_of(SearchBar.BINDINGS)),
        ("Node panel", bindings_of(NodePane.BINDINGS)),
        ("Marks", bindings_of(MarksScreen.BINDINGS)),
        ("Rules pane", bindings_of(RulesPane.BINDINGS)),
        ("Query line", bindings_of(QueryBar.BINDINGS)),
        ("Logger levels pane", bindings_of(LoggerPane.BINDINGS)),
        ("Timeline", bindings_of(TimelineStrip.BINDINGS)),
        ("Summary", bindings_of(SummaryScreen.BINDINGS)),
        ("Details", bindings_of(DetailScreen.BINDINGS)),
        ("Anywhere", [Binding("ctrl+p", "command_palette", "Command palette: every action by name")]),
    ]
