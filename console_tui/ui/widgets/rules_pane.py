"""The rules pane: every exclude and highlight rule, its switches and its match count."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from rich.style import Style
from rich.table import Table
from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.message import Message
from textual.widget import Widget
from textual.widgets import Label, OptionList, Static
from textual.widgets.option_list import Option

from ...model.inert_text import one_line
from ...model.rules.ruleset import Entry, Role, RuleSet
from ..keys import Hint, hint_line
from .side_pane import SidePane

_HINTS: list[Hint] = [
    ("toggle_enabled", "on/off"),
    ("toggle_inverted", "invert"),
    ("toggle_role", "exclude⇄highlight"),
    ("edit", "edit"),
    ("delete", "delete"),
    ("add", "add"),
    ("console.highlighted_only", "highlighted only"),
    ("save_rules", "save"),
    ("load_rules", "open"),
    ("leave", "table"),
]


#: How the pane names the rules the level and node keys make (``model/rules/key_rules.py``).
_TOGGLE_NAMES = {"levels": "level keys", "solo": "solo", "mute": "mute"}


def entry_text(entry: Entry, count: int | None, styles: Mapping[str, Style] | None = None) -> Table:
    """One entry of the list: on/off, role, the rule (wrapping when long), and at the right
    of its first line its count, or why it is inactive; ``styles`` are the pane's component classes."""

    def look(name: str) -> Style:
        return (styles or {}).get(f"rules-pane--{name}", _PLAIN)

    text = Text()
    text.append("● " if entry.enabled else "○ ", style=look("on" if entry.enabled else "off"))
    if entry.role is Role.EXCLUDE:
        text.append("hide ", style=look("hide"))
    else:
        text.append("mark ", style=look("mark"))
    description = one_line(entry.describe(), 200)
    text.append(description, style=_PLAIN if entry.active else look("inactive" if entry.enabled else "off-rule"))
    if entry.from_query:
        text.append("  (query)", style=look("aside"))
    if entry.toggle:
        text.append(f"  ({_TOGGLE_NAMES.get(entry.toggle, entry.toggle)})", style=look("aside"))
    if count is None and entry.enabled and entry.rule.is_empty:
        text.append("  (empty: matches nothing)", style=look("aside"))
    row = Table.grid(expand=True)
    row.add_column(ratio=1, overflow="fold")
    row.add_column(justify="right", no_wrap=True)
    row.add_row(text, Text(f" {count:,}", style=look("count")) if count is not None else "")
    return row


_PLAIN = Style()


class RulesPane(SidePane):
    """Lists a ``RuleSet``; every change is posted as a new set (the app applies it).

    | Key(s) | Description |
    | :- | :- |
    | space | Switch the highlighted rule on or off. |
    | i | Invert it. |
    | h | Exclude or highlight. |
    | e, enter | Edit it (``EditRequested``). |
    | d, delete | Delete it. |
    | a | Add a rule (``EditRequested``). |
    | S / O | Save the rule set / open one (``FileRequested``). |
    | escape | Back to the table. |

    | Class | Description |
    | :- | :- |
    | `rules-pane--on` / `rules-pane--off` | The mark of a rule switched on / off. |
    | `rules-pane--hide` / `rules-pane--mark` | An exclude / a highlight rule's role. |
    | `rules-pane--inactive` | A rule switched on that does nothing yet. |
    | `rules-pane--off-rule` | A rule switched off. |
    | `rules-pane--count` | How many messages a rule matches. |
    | `rules-pane--aside` | "(query)", "(level keys)", "(empty: matches nothing)". |
    """

    COMPONENT_CLASSES = {
        "rules-pane--on",
        "rules-pane--off",
        "rules-pane--hide",
        "rules-pane--mark",
        "rules-pane--inactive",
        "rules-pane--off-rule",
        "rules-pane--count",
        "rules-pane--aside",
    }

    DEFAULT_CSS = """
    RulesPane > .rules-pane--on { color: $text-success; text-style: bold; }
    RulesPane > .rules-pane--off { color: $foreground-muted; }
    RulesPane > .rules-pane--hide { color: $text-error; text-style: bold; }
    RulesPane > .rules-pane--mark { color: $text-warning; text-style: bold; }
    RulesPane > .rules-pane--inactive { color: $foreground-muted; }
    RulesPane > .rules-pane--off-rule { color: $foreground-muted; text-style: strike; }
    RulesPane > .rules-pane--count { color: $text-accent; text-style: bold; }
    RulesPane > .rules-pane--aside { color: $foreground-muted; text-style: italic; }
    RulesPane { dock: left; width: 52; max-width: 50%; border-right: vkey $primary; padding: 0 1; background: $surface; }
    RulesPane > .title { text-style: bold; color: $accent; }
    RulesPane > OptionList { height: 1fr; border: none; padding: 0; background: $surface; }
    RulesPane > #rules-state { color: $text-muted; height: auto; }
    RulesPane > #rules-hint { color: $text-muted; height: auto; }
    """

    BINDINGS = [
        Binding("space", "toggle_enabled", "On/off", show=False, id="rules.on_off"),
        Binding("i", "toggle_inverted", "Invert", show=False, id="rules.invert"),
        Binding("h", "toggle_role", "Exclude/highlight", show=False, id="rules.role"),
        Binding("e,enter", "edit", "Edit", show=False, id="rules.edit"),
        Binding("d,delete", "delete", "Delete", show=False, id="rules.delete"),
        Binding("a", "add", "Add rule", show=False, id="rules.add"),
        Binding("S", "save_rules", "Save rule set", show=False, id="rules.save"),
        Binding("O", "load_rules", "Open rule set", show=False, id="rules.open"),
        Binding("escape", "leave", "Back to the table", show=False, id="rules.leave"),
    ]

    @dataclass
    class Changed(Message):
        """The user changed the rules through the pane."""

        rules: RuleSet

    @dataclass
    class EditRequested(Message):
        """Open the rule editor: on entry ``index``, or for a new rule (None)."""

        index: int | None

    @dataclass
    class FileRequested(Message):
        """Save the rule set to a file, or open one (``save`` False)."""

        save: bool

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.rules = RuleSet()
        self.counts: list[int | None] = []
        self.progress = ""
        self._drawn = False

    def compose(self) -> ComposeResult:
        yield Label("Rules", classes="title")
        yield Static("", id="rules-state")
        yield OptionList(id="rules-list")
        # The app's keys that work here too ("highlighted only") come from the app's bindings.
        yield Static(hint_line(self.app, [*self.BINDINGS, *self.app.BINDINGS], _HINTS), id="rules-hint")

    def focus_target(self) -> Widget:
        return self.query_one(OptionList)

    def show(self, rules: RuleSet, counts: list[int | None], progress: str = "") -> None:
        """Show these rules with these counts (only redrawn when something changed)."""
        unchanged = rules == self.rules and counts == self.counts and progress == self.progress
        if unchanged and self._drawn:
            return
        self.rules, self.counts, self.progress = rules, list(counts), progress
        if self.is_mounted:
            self._draw()

    def on_mount(self) -> None:
        self._draw()

    def _draw(self) -> None:
        self._drawn = True
        rules, counts, progress = self.rules, self.counts, self.progress
        options = self.query_one(OptionList)
        styles = {name: self.get_component_rich_style(name, partial=True) for name in self.COMPONENT_CLASSES}
        highlighted = options.highlighted
        options.clear_options()
        if rules.entries:
            options.add_options(
                [
                    Option(entry_text(entry, counts[i] if i < len(counts) else None, styles), id=str(i))
                    for i, entry in enumerate(rules.entries)
                ]
            )
            options.highlighted = min(highlighted or 0, len(rules.entries) - 1)
        else:
            options.add_option(
                Option(Text("No rules. a adds one; / types a query; - or + on a row.", style="dim"), disabled=True)
            )
        state = f"highlighted only: {'ON' if rules.highlighted_only else 'off'}"
        if progress:
            state += f" · {progress}"
        self.query_one("#rules-state", Static).update(state)

    @property
    def selected(self) -> int | None:
        index = self.query_one(OptionList).highlighted
        if index is None or not self.rules.entries or index >= len(self.rules.entries):
            return None
        return index

    def _change(self, rules: RuleSet) -> None:
        self.post_message(self.Changed(rules))

    def action_toggle_enabled(self) -> None:
        index = self.selected
        if index is not None:
            self._change(self.rules.with_enabled(index, not self.rules.entries[index].enabled))

    def action_toggle_inverted(self) -> None:
        index = self.selected
        if index is not None:
            self._change(self.rules.with_inverted(index, not self.rules.entries[index].inverted))

    def action_toggle_role(self) -> None:
        index = self.selected
        if index is not None:
            role = Role.HIGHLIGHT if self.rules.entries[index].role is Role.EXCLUDE else Role.EXCLUDE
            self._change(self.rules.with_role(index, role))

    def action_delete(self) -> None:
        index = self.selected
        if index is not None:
            self._change(self.rules.remove(index))

    def action_edit(self) -> None:
        index = self.selected
        if index is not None:
            self.post_message(self.EditRequested(index))

    def action_add(self) -> None:
        self.post_message(self.EditRequested(None))

    def action_save_rules(self) -> None:
        self.post_message(self.FileRequested(save=True))

    def action_load_rules(self) -> None:
        self.post_message(self.FileRequested(save=False))

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self.action_edit()
