"""Quick rules from the selected rows: exclude or highlight their nodes, severities, messages
or location."""

from __future__ import annotations

import os
import re
from collections.abc import Sequence

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Label, OptionList
from textual.widgets.option_list import Option

from ...model.inert_text import one_line
from ...model.levels import severity_name
from ...model.rules.location import LocationRule
from ...model.rules.message import MessageRule
from ...model.rules.node import NodeRule
from ...model.rules.rule import Rule
from ...model.rules.ruleset import Entry, Role
from ...model.rules.severity import SeverityRule
from ...model.store.record import LogRecord
from ..focus import focus_now
from ..keys import Hint, hint_line
from ..plain import plain

#: At most this many distinct messages make one "these messages" rule.
MESSAGES_AT_MOST = 50


def quick_rules(records: Sequence[LogRecord]) -> list[tuple[str, Rule]]:
    """What selected rows offer, with a label each: their nodes, severities, messages and
    (when they share it) location."""
    nodes = list(dict.fromkeys(record.node for record in records))
    levels = sorted({record.level for record in records})
    messages = list(dict.fromkeys(record.msg for record in records))
    locations = {(record.file, record.function, record.line) for record in records}
    choices: list[tuple[str, Rule]] = [
        (_label("node", nodes), NodeRule(tuple(nodes))),
        (_label("severity", [severity_name(level) for level in levels]), SeverityRule(frozenset(levels))),
    ]
    if len(messages) == 1:
        choices.append((_label("message", messages), MessageRule(messages[0])))
    elif len(messages) <= MESSAGES_AT_MOST:
        any_of = "|".join(re.escape(message) for message in messages)
        choices.append((_label("message", messages), MessageRule(any_of, regex=True)))
    if len(locations) == 1:
        file, function, line = locations.pop()
        where = f"{os.path.basename(file)}:{function}:{line}"
        choices.append((_label("location", [where]), LocationRule(file=file, function=function, line=line or None)))
    return choices


def _label(kind: str, values: Sequence[str]) -> str:
    if len(values) == 1:
        return f"this {kind}: {values[0]}"
    plural = "severities" if kind == "severity" else f"{kind}s"
    return f"these {len(values)} {plural}: " + ", ".join(one_line(value, 40) for value in values)


class QuickRuleScreen(ModalScreen[Entry | None]):
    """A short menu; returns the chosen rule as an exclude or highlight entry.

    | Key(s) | Description |
    | :- | :- |
    | escape | Cancel. |
    """

    DEFAULT_CSS = """
    QuickRuleScreen { align: center middle; }
    QuickRuleScreen > Vertical { width: 80; max-width: 95%; height: auto; border: thick $primary; background: $surface; padding: 0 1; }
    QuickRuleScreen OptionList { height: auto; max-height: 10; }
    """
    BINDINGS = [Binding("escape", "cancel", "Cancel")]

    def __init__(self, records: Sequence[LogRecord], role: Role) -> None:
        super().__init__()
        self.role = role
        self.choices = quick_rules(records)

    def compose(self) -> ComposeResult:
        verb = "Hide" if self.role is Role.EXCLUDE else "Highlight"
        with Vertical():
            hints: list[Hint] = [("select", "picks"), ("cancel", "cancels")]
            yield Label(
                f"{verb} messages with... ({hint_line(self.app, [*OptionList.BINDINGS, *self.BINDINGS], hints)})"
            )
            yield OptionList(*(Option(plain(label, limit=200), id=str(i)) for i, (label, _) in enumerate(self.choices)))

    def on_mount(self) -> None:
        focus_now(self.query_one(OptionList))

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        _, rule = self.choices[event.option_index]
        self.dismiss(Entry(rule, self.role))

    def action_cancel(self) -> None:
        self.dismiss(None)
