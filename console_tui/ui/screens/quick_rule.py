"""Quick rules from a row: exclude or highlight its node, severity, message or location."""

from __future__ import annotations

import os

from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Label, OptionList
from textual.widgets.option_list import Option

from ...model.levels import severity_name
from ...model.record import LogRecord
from ...model.rules.base import Rule
from ...model.rules.location import LocationRule
from ...model.rules.message import MessageRule
from ...model.rules.node import NodeRule
from ...model.rules.ruleset import Entry, Role
from ...model.rules.severity import SeverityRule
from ...model.text import one_line


def quick_rules(record: LogRecord) -> list[tuple[str, Rule]]:
    """What a row offers, with a label each: its node, severity, message and location."""
    return [
        (f"this node: {record.node}", NodeRule((record.node,))),
        (f"this severity: {severity_name(record.level)}", SeverityRule(frozenset({record.level}))),
        (f"this message: {record.msg}", MessageRule(record.msg)),
        (
            f"this location: {os.path.basename(record.file)}:{record.function}:{record.line}",
            LocationRule(file=record.file, function=record.function, line=record.line or None),
        ),
    ]


class QuickRuleScreen(ModalScreen[Entry | None]):
    """A short menu; returns the chosen rule as an exclude or highlight entry."""

    DEFAULT_CSS = """
    QuickRuleScreen { align: center middle; }
    QuickRuleScreen > Vertical { width: 80; max-width: 95%; height: auto; border: thick $primary; background: $surface; padding: 0 1; }
    QuickRuleScreen OptionList { height: auto; max-height: 10; }
    """
    BINDINGS = [Binding("escape", "cancel", "Cancel")]

    def __init__(self, record: LogRecord, role: Role) -> None:
        super().__init__()
        self.role = role
        self.choices = quick_rules(record)

    def compose(self) -> ComposeResult:
        verb = "Hide" if self.role is Role.EXCLUDE else "Highlight"
        with Vertical():
            yield Label(f"{verb} messages with... (Enter picks, Esc cancels)")
            yield OptionList(*(Option(one_line(label, 200), id=str(i)) for i, (label, _) in enumerate(self.choices)))

    def on_mount(self) -> None:
        self.query_one(OptionList).focus()

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        _, rule = self.choices[event.option_index]
        self.dismiss(Entry(rule, self.role))

    def action_cancel(self) -> None:
        self.dismiss(None)
