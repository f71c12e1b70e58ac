"""The keys that find your way (``ConsoleApp.BINDINGS`` places them, for the footer's order,
and the help screen shows them as a group): search, jumps, marks, levels, nodes, time."""

from __future__ import annotations

from textual.binding import Binding

from ..model.levels import MESSAGE_SEVERITIES

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
