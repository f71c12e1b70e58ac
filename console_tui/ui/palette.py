"""The command palette's entries (Ctrl+P): every action by name, with its key.

An entry names an app action (run with ``App.run_action``) and, when a key does the same,
the id of that key's binding: the palette shows the key as the bindings (and the user's
keymap) say. A new feature adds its entries to ``palette_commands``.

What a person types is looked for in the title, then in the words people use for the entry
(``words``: "search" finds Find, "editor" the source file), then in its help; an entry that
ends an action (``ends``: clear the search) ranks below the one that starts it.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from functools import partial
from typing import Protocol, cast

from textual.binding import Binding
from textual.command import DiscoveryHit, Hit, Hits, Provider

from ..model.levels import MESSAGE_SEVERITIES
from ..model.time_column import FORMATS, format_info
from .keys import KeyDisplay, key_label, keymap_of
from .widgets.table_columns import COLUMNS


@dataclass(frozen=True)
class PaletteCommand:
    title: str
    help: str
    #: An action of the app: ``toggle_pause``, ``quick_rule('exclude')``.
    action: str
    #: The id of the binding that does the same, whose key is shown.
    key: str | None = None
    #: Other words people look for it by (searched as the title is).
    words: str = ""
    #: It ends or undoes what another entry starts (it ranks below that one).
    ends: bool = False


def palette_commands() -> list[PaletteCommand]:
    """Every entry, in the order the palette lists them before anything is typed."""
    C = PaletteCommand
    return [
        C("Pause / resume", "Stop the view; messages keep arriving", "toggle_pause", "console.pause"),
        C("Follow tail", "Jump to the newest message and follow it", "follow", "table.follow"),
        C("Clear", "Drop every message", "clear", "console.clear"),
        C("Details", "Every field of the selected message; y copies it", "details", "table.details", "copy yank"),
        C("Columns", "Choose the table's columns", "columns", "console.columns"),
        C("Open files", "Log files and recordings, merged by time", "open", "console.open"),
        C(
            "Save",
            "Save the rows shown, or everything (rqt_console CSV or JSON Lines)",
            "save",
            "console.save",
            "export write",
        ),
        C("Load problems", "What went wrong while loading files, and where", "problems", "console.problems"),
        *(
            C(
                f"Toggle column: {column.title}",
                f"Show or hide the {column.title} column",
                f"toggle_column('{column.key}')",
            )
            for column in COLUMNS
            if column.key != "message"
        ),
        C("Logger levels", "Show or hide the logger levels pane", "toggle_loggers", "console.loggers"),
        C(
            "Logger levels of this row's node",
            "Open the logger levels pane on the selected row's node",
            "loggers_for_row",
            "console.loggers_for_row",
        ),
        C(
            "Query",
            'Type rules as a query: level>=warn node:nav* -node:rviz* +"failed"',
            "query",
            "console.query",
            "filter",
        ),
        C(
            "Rules",
            "Show or hide the rules pane: every rule, its switches and counts",
            "toggle_rules",
            "console.rules",
            "filter",
        ),
        C("Add a rule", "A new exclude or highlight rule of any kind", "add_rule", words="filter"),
        C(
            "Hide messages like the selected rows",
            "Exclude their nodes, severities, messages or location",
            "quick_rule('exclude')",
            "console.hide_like",
        ),
        C(
            "Highlight messages like the selected rows",
            "Highlight their nodes, severities, messages or location",
            "quick_rule('highlight')",
            "console.highlight_like",
        ),
        C(
            "Highlighted only",
            "Show only highlighted messages (or all again)",
            "toggle_highlighted_only",
            "console.highlighted_only",
        ),
        C("Save rules", "Save the rule set to a TOML file", "save_rules"),
        C("Open rules", "Load a rule set from a TOML file", "load_rules"),
        C("Restore the last rules", "The rule set in force when console-tui last exited", "restore_rules"),
        C("Clear rules", "Remove every rule", "clear_rules", words="filter", ends=True),
        *navigation_commands(),
        C(
            "Timeline: pick a time",
            "The rate by severity over the whole history; Enter shows a time",
            "timeline",
            "overview.timeline",
        ),
        C(
            "Show / hide the timeline",
            "The strip of the message rate above the table",
            "toggle_timeline",
            "overview.toggle_timeline",
        ),
        C(
            "Expand / collapse this storm",
            "The repeats of the selected row's message, each a row",
            "toggle_storm",
            "overview.storm",
        ),
        C(
            "Storms collapsed on / off",
            "A node's repeats of one message as one row (×N), or every message a row",
            "toggle_storms",
            "overview.storms",
        ),
        C("Storms: digits count as the same", "'took 12 ms' repeats 'took 9 ms' (on / off)", "toggle_mask_digits"),
        C(
            "Summary",
            "Counts per severity and node, the busiest nodes, the first ERROR and FATAL",
            "summary",
            "overview.summary",
        ),
        C("Help: every key", "What console-tui shows, and every key (remap them in keys.toml)", "help", "console.help"),
    ]


def navigation_commands() -> list[PaletteCommand]:
    """Search, jumps, marks, level and node toggles, time formats, the source file."""
    C = PaletteCommand
    return [
        C(
            "Find",
            "Search a text or /regex/ in the messages; the rows stay, matches are marked",
            "search",
            "nav.find",
            "search grep look",
        ),
        C("Next match", "The next row the search matches, below", "next_match", "nav.next_match"),
        C("Previous match", "The previous row the search matches, above", "previous_match", "nav.previous_match"),
        C("Clear the search", "No search: no marks, no counter", "clear_search", "console.clear_search", ends=True),
        C("Next error", "The next ERROR or FATAL below", "next_level(40)", "nav.next_error"),
        C("Previous error", "The previous ERROR or FATAL above", "previous_level(40)", "nav.previous_error"),
        C("Next warning", "The next WARN or worse below", "next_level(30)", "nav.next_warning"),
        C("Previous warning", "The previous WARN or worse above", "previous_level(30)", "nav.previous_warning"),
        C("First message", "The oldest row", "first_row", "table.first"),
        C("Last message", "The newest row, and follow", "last_row", "table.follow"),
        C("Mark the row", "Put a mark on the selected row (or take it off)", "toggle_mark", "nav.mark"),
        C("Next mark", "The next marked row below", "next_mark", "nav.next_mark"),
        C("Previous mark", "The previous marked row above", "previous_mark", "nav.previous_mark"),
        C("Marks", "Every marked row; go to one", "marks", "nav.marks"),
        *(
            C(
                f"Show / hide {severity.name}",
                f"Hide {severity.name} messages, or show them again (a rule underneath)",
                f"toggle_level({int(severity)})",
                f"levels.{severity.name.lower()}",
            )
            for severity in MESSAGE_SEVERITIES
        ),
        *(
            C(f"Minimum level: {severity.name}", f"Show {severity.name} and worse", f"minimum_level({int(severity)})")
            for severity in MESSAGE_SEVERITIES
        ),
        C("Minimum level up", "Hide the lowest level shown", "raise_minimum", "levels.up"),
        C("Minimum level down", "Show one more level", "lower_minimum", "levels.down"),
        C("Every level", "Show every level again", "all_levels", "levels.all", "severity level"),
        C("Nodes", "The node panel: every node, its counts and rate; solo, mute", "toggle_nodes", "console.nodes"),
        C("Solo this row's node", "Show only the selected row's node (again: undo)", "solo_row_node"),
        C("Mute this row's node", "Hide the selected row's node (again: undo)", "mute_row_node"),
        C("Every node heard", "No node soloed or muted", "clear_node_toggles"),
        *(
            C(
                f"Time: {format_info(fmt).name}",
                f"The Time column shows the {format_info(fmt).name}",
                f"time_format('{fmt.value}')",
            )
            for fmt in FORMATS
        ),
        C(
            "Time format: the next one",
            "Wall clock, date, stamp, since first, since row, delta",
            "next_time_format",
            "time.format",
        ),
        C("Time in UTC / local time", "The wall clock in UTC, or local time", "toggle_utc", "time.utc"),
        C(
            "Open the source file",
            "The row's file in $VISUAL / $EDITOR at its line",
            "open_source",
            "nav.source",
            "editor code vim",
        ),
    ]


class KeyedApp(KeyDisplay, Protocol):
    """What the palette reads of the app (``ConsoleApp``): its keys, by where they work."""

    def binding_groups(self) -> list[tuple[str, list[Binding]]]: ...


class PaletteProvider(Provider):
    """The palette entries of ``palette_commands``, each shown with its key."""

    @property
    def console(self) -> KeyedApp:
        return cast(KeyedApp, self.app)  # only ConsoleApp lists this provider

    def _entries(self) -> Iterable[tuple[PaletteCommand, str]]:
        app = self.console
        bindings = {binding.id: binding for _title, group in app.binding_groups() for binding in group if binding.id}
        keymap = keymap_of(app)
        for command in palette_commands():
            binding = bindings.get(command.key) if command.key else None
            key = key_label(binding, app, keymap) if binding is not None else ""
            yield command, f"{command.help}  ({key})" if key else command.help

    async def discover(self) -> Hits:
        for command, help_text in self._entries():
            yield DiscoveryHit(command.title, partial(self.app.run_action, command.action), help=help_text)

    async def search(self, query: str) -> Hits:
        matcher = self.matcher(query)
        for command, help_text in self._entries():
            score = palette_score(command, query, matcher.match)
            if score > 0:
                yield Hit(
                    score,
                    matcher.highlight(command.title),
                    partial(self.app.run_action, command.action),
                    text=command.title,
                    help=help_text,
                )


def _words(text: str) -> list[str]:
    return re.findall(r"[a-z0-9]+", text.lower())


def palette_score(command: PaletteCommand, query: str, fuzzy: Callable[[str], float]) -> float:
    """How well ``command`` answers what was typed (0: not at all): every typed word starting
    a word of the title scores highest, of its other words next, of its help after them; else
    the title's fuzzy match (``fuzzy``), lower. An entry that ends an action ranks lower."""
    typed = _words(query)

    def holds(text: str) -> bool:
        words = _words(text)
        return bool(typed) and all(any(word.startswith(part) for word in words) for part in typed)

    if holds(command.title):
        score = 1.0
    elif holds(command.words):
        score = 0.9
    elif holds(command.help):
        score = 0.8
    else:
        score = 0.7 * fuzzy(command.title)
    return score * 0.6 if command.ends else score
