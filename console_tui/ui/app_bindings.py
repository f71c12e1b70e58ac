"""The console's keys (``ConsoleApp.BINDINGS``), in the footer's order, and every key of the
app by where it works (the help screen, the keymap and the palette read ``key_groups``).

The keys that find your way (search, jumps, marks, levels, nodes, time) are a group of their
own in the help screen.
"""

from __future__ import annotations

from collections.abc import Iterable

from textual.binding import Binding, BindingType

from ..model.levels import MESSAGE_SEVERITIES
from .widgets.log_table import LogTable
from .widgets.logger_pane import LoggerPane
from .widgets.node_pane import NodePane
from .widgets.query_bar import QueryBar
from .widgets.rules_pane import RulesPane
from .widgets.search_bar import SearchBar
from .widgets.timeline_strip import TimelineStrip

SEARCH_KEYS = [
    Binding("f,ctrl+f", "search", "Find", id="nav.find"),
    Binding("n", "next_match", "Next match", show=False, id="nav.next_match"),
    Binding("N", "previous_match", "Previous match", show=False, id="nav.previous_match"),
]

JUMP_KEYS = [
    Binding("e", "next_level(40)", "Next ERROR or worse", show=False, id="nav.next_error"),
    Binding("E", "previous_level(40)", "Previous ERROR or worse", show=False, id="nav.previous_error"),
    Binding("w", "next_level(30)", "Next WARN or worse", show=False, id="nav.next_warning"),
    Binding("W", "previous_level(30)", "Previous WARN or worse", show=False, id="nav.previous_warning"),
    Binding("m", "toggle_mark", "Mark the row (or unmark it)", show=False, id="nav.mark"),
    Binding("u", "next_mark", "Next mark", show=False, id="nav.next_mark"),
    Binding("U", "previous_mark", "Previous mark", show=False, id="nav.previous_mark"),
    Binding("M", "marks", "Marks: list them, jump to one", show=False, id="nav.marks"),
    Binding("v", "open_source", "Open the row's source file in $VISUAL / $EDITOR", show=False, id="nav.source"),
]

TOGGLE_KEYS = [
    *(
        Binding(
            str(number),
            f"toggle_level({int(severity)})",
            f"Show / hide {severity.name} messages",
            show=False,
            id=f"levels.{severity.name.lower()}",
        )
        for number, severity in enumerate(MESSAGE_SEVERITIES, start=1)
    ),
    Binding(
        "greater_than_sign", "raise_minimum", "Minimum level up (hide the lowest shown)", show=False, id="levels.up"
    ),
    Binding("less_than_sign", "lower_minimum", "Minimum level down (show one more)", show=False, id="levels.down"),
    Binding("0", "all_levels", "Every level shown again", show=False, id="levels.all"),
    Binding(
        "t",
        "next_time_format",
        "Time format: clock, date, stamp, since first, since row, Δ",
        show=False,
        id="time.format",
    ),
    Binding("ctrl+u", "toggle_utc", "Time in UTC / local time", show=False, id="time.utc"),
]

#: Every key that finds your way.
NAV_KEYS = [*SEARCH_KEYS, *JUMP_KEYS, *TOGGLE_KEYS]

APP_BINDINGS: list[BindingType] = [
    # One key, two bindings: check_action shows the one that applies (Resume while paused);
    # one id, so that a keymap moves both.
    Binding("space", "pause", "Pause", id="console.pause"),
    Binding("space", "resume", "Resume", id="console.pause"),
    Binding("c", "clear", "Clear", id="console.clear"),
    Binding("o", "open", "Open", id="console.open"),
    Binding("s", "save", "Save", id="console.save"),
    Binding("x", "cancel_load", "Cancel load", id="console.cancel_load"),
    Binding("escape", "stop_filtering", "Stop a long filtering", show=False, id="console.stop_filtering"),
    Binding("escape", "clear_search", "Clear the search", show=False, id="console.clear_search"),
    Binding("exclamation_mark", "problems", "Problems", show=False, id="console.problems"),
    Binding("slash", "query", "Query", id="console.query"),
    *SEARCH_KEYS,
    Binding("r", "toggle_rules", "Rules", id="console.rules"),
    Binding("H", "toggle_highlighted_only", "Highlighted only", show=False, id="console.highlighted_only"),
    Binding("minus", "quick_rule('exclude')", "Hide like the selected rows", show=False, id="console.hide_like"),
    Binding(
        "plus",
        "quick_rule('highlight')",
        "Highlight like the selected rows",
        show=False,
        id="console.highlight_like",
    ),
    Binding("C", "columns", "Columns", id="console.columns"),
    Binding("l", "toggle_loggers", "Loggers", id="console.loggers"),
    Binding("ctrl+n", "toggle_nodes", "Nodes", id="console.nodes"),
    Binding("L", "loggers_for_row", "Logger levels of the row's node", show=False, id="console.loggers_for_row"),
    Binding("T", "timeline", "Timeline: pick a time to show", show=False, id="overview.timeline"),
    Binding("ctrl+t", "toggle_timeline", "Show / hide the timeline", show=False, id="overview.toggle_timeline"),
    Binding("z", "toggle_storm", "Expand / collapse the row's storm", show=False, id="overview.storm"),
    Binding("Z", "toggle_storms", "Storms collapsed on / off", show=False, id="overview.storms"),
    Binding("S", "summary", "Summary of the run", show=False, id="overview.summary"),
    Binding("question_mark,f1", "help", "Help", id="console.help"),
    Binding("q", "quit", "Quit", id="console.quit"),
    Binding("ctrl+c", "quit", "Quit", show=False),
    *JUMP_KEYS,
    *TOGGLE_KEYS,
]


def bindings_of(bindings: Iterable[BindingType]) -> list[Binding]:
    return [binding for binding in bindings if isinstance(binding, Binding)]


def key_groups() -> list[tuple[str, list[Binding]]]:
    """Every key, by where it works."""
    # The dialogs' screens load when first needed, not with the first frame (keys.load_keymap).
    from .screens.detail import DetailScreen
    from .screens.mark_list import MarksScreen
    from .screens.summary import SummaryScreen

    nav = bindings_of(NAV_KEYS)
    return [
        ("Table", bindings_of(LogTable.BINDINGS)),
        # Space's Resume is its Pause while paused: one row.
        ("Console", [b for b in bindings_of(APP_BINDINGS) if b not in nav and b.action != "resume"]),
        ("Find your way", nav),
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
