"""Making or editing one rule: its kind's fields, exclude or highlight, inverted."""

from __future__ import annotations

from typing import TypeVar

from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Horizontal, Vertical
from textual.screen import ModalScreen
from textual.widgets import Checkbox, Input, Label, RadioSet, Select

from ...model.levels import MESSAGE_SEVERITIES
from ...model.rules.custom import CustomRule
from ...model.rules.location import LocationRule
from ...model.rules.message import MessageRule
from ...model.rules.node import NodeRule
from ...model.rules.query import parse_time
from ...model.rules.robot import RobotRule
from ...model.rules.rule import Rule, RuleError
from ...model.rules.ruleset import Entry, Role
from ...model.rules.severity import SeverityRule
from ...model.rules.time_range import TimeRangeRule
from ...model.timefmt import full_text
from ..keys import Hint, hint_line
from ..plain import plain
from ..widgets.marked_buttons import MarkedCheckbox, MarkedRadioButton

KINDS = {
    "message": "Message text",
    "severity": "Severities",
    "node": "Nodes",
    "robot": "Robots (of a fleet)",
    "location": "Location (file, function, line)",
    "time": "Time range",
    "custom": "Custom: all of the fields below",
}
#: Which field groups each kind shows.
GROUPS = {
    "message": ("message",),
    "severity": ("severity",),
    "node": ("node",),
    "robot": ("robot",),
    "location": ("location",),
    "time": ("time",),
    "custom": ("message", "severity", "node", "robot", "location", "time"),
}


def _parts(rule: Rule) -> dict[str, Rule]:
    parts = rule.parts if isinstance(rule, CustomRule) else (rule,)
    return {part.kind: part for part in parts}


_Part = TypeVar("_Part", bound=Rule)


def _part(parts: dict[str, Rule], kind: type[_Part]) -> _Part:
    """The part of that kind, or an empty one."""
    part = parts.get(kind.kind)
    return part if isinstance(part, kind) else kind()


class RuleEditor(ModalScreen[Entry | None]):
    """Returns the new entry, or None when cancelled. A rule that cannot be made (a bad
    regex, a bad time) says why here, and nothing changes until it is fixed.

    | Key(s) | Description |
    | :- | :- |
    | escape | Cancel. |
    | ctrl+s, f2 | Apply (Enter in a field too). |
    """

    DEFAULT_CSS = """
    RuleEditor { align: center middle; }
    RuleEditor > Vertical { width: 84; max-width: 98%; height: auto; max-height: 98%; border: thick $primary; background: $surface; padding: 0 1; overflow-y: auto; }
    RuleEditor .group { height: auto; margin-top: 1; }
    RuleEditor .group.-hidden { display: none; }
    RuleEditor Horizontal { height: auto; }
    RuleEditor Input { width: 1fr; }
    RuleEditor #rule-error { color: $text-error; height: auto; width: 100%; }
    RuleEditor RadioSet { layout: horizontal; height: auto; }
    """
    BINDINGS = [Binding("escape", "cancel", "Cancel"), Binding("ctrl+s,f2", "apply", "Apply")]

    def __init__(
        self, entry: Entry | None = None, *, kind: str = "message", role: Role = Role.EXCLUDE, utc: bool = False
    ) -> None:
        super().__init__()
        self.entry = entry
        self.kind = entry.rule.kind if entry is not None else kind
        self.role = entry.role if entry is not None else role
        self.utc = utc

    def compose(self) -> ComposeResult:
        parts = _parts(self.entry.rule) if self.entry is not None else {}
        message = _part(parts, MessageRule)
        severity = _part(parts, SeverityRule)
        node = _part(parts, NodeRule)
        robot = _part(parts, RobotRule)
        location = _part(parts, LocationRule)
        period = _part(parts, TimeRangeRule)
        with Vertical():
            yield Label("Edit rule" if self.entry is not None else "New rule", classes="title")
            yield Select([(title, key) for key, title in KINDS.items()], value=self.kind, allow_blank=False, id="kind")
            with RadioSet(id="role"):
                yield MarkedRadioButton("Exclude", value=self.role is Role.EXCLUDE, name="exclude")
                yield MarkedRadioButton("Highlight", value=self.role is Role.HIGHLIGHT, name="highlight")
            yield MarkedCheckbox(
                "Inverted: matches what the rule does not",
                value=bool(self.entry and self.entry.inverted),
                id="inverted",
            )
            with Vertical(classes="group", id="group-message"):
                yield Input(message.text, placeholder="text the message contains", id="message-text")
                with Horizontal():
                    yield MarkedCheckbox("Ignore case", value=message.ignore_case, id="message-ignore-case")
                    yield MarkedCheckbox("Regular expression", value=message.regex, id="message-regex")
            with Horizontal(classes="group", id="group-severity"):
                for level in MESSAGE_SEVERITIES:
                    yield MarkedCheckbox(
                        level.name, value=int(level) in severity.levels, id=f"severity-{level.name.lower()}"
                    )
            with Vertical(classes="group", id="group-node"):
                yield Input(
                    ", ".join(node.names),
                    placeholder="node names or globs, comma separated: nav*, /ns/talker",
                    id="node-names",
                )
            with Vertical(classes="group", id="group-robot"):
                yield Input(
                    ", ".join(robot.names), placeholder="robots' names or globs, comma separated", id="robot-names"
                )
            with Vertical(classes="group", id="group-location"):
                with Horizontal():
                    yield Input(location.file, placeholder="file contains", id="location-file")
                    yield Input(location.function, placeholder="function contains", id="location-function")
                    yield Input(
                        "" if location.line is None else str(location.line), placeholder="line", id="location-line"
                    )
                with Horizontal():
                    yield MarkedCheckbox("Ignore case", value=location.ignore_case, id="location-ignore-case")
                    yield MarkedCheckbox("Regular expressions", value=location.regex, id="location-regex")
            with Horizontal(classes="group", id="group-time"):
                yield Input(
                    self._time(period.start_ns),
                    placeholder="from (12:30, 2024-05-01T12:30, 5m); empty: open",
                    id="time-from",
                )
                yield Input(self._time(period.end_ns), placeholder="to; empty: open", id="time-to")
            yield Label("", id="rule-error")
            hints: list[Hint] = [(("submit", "apply"), "applies"), ("cancel", "cancels")]
            yield Label(hint_line(self.app, [*Input.BINDINGS, *self.BINDINGS], hints), classes="hint")

    def _time(self, stamp: int | None) -> str:
        return "" if stamp is None else full_text(stamp, utc=self.utc).rsplit(" ", 1)[0].replace(" ", "T")

    def on_mount(self) -> None:
        self._show_groups()
        self.query_one("#kind", Select).focus()

    @on(Select.Changed, "#kind")
    def kind_changed(self, event: Select.Changed) -> None:
        self.kind = str(event.value)
        self._show_groups()

    def _show_groups(self) -> None:
        shown = GROUPS[self.kind]
        for group in ("message", "severity", "node", "robot", "location", "time"):
            self.query_one(f"#group-{group}").set_class(group not in shown, "-hidden")

    @on(Input.Submitted)
    def submitted(self) -> None:
        self.action_apply()

    def action_cancel(self) -> None:
        self.dismiss(None)

    def action_apply(self) -> None:
        try:
            rule = self.build_rule()
        except RuleError as error:
            self.query_one("#rule-error", Label).update(plain(f"Not applied: {error.message}"))
            return
        pressed = self.query_one("#role", RadioSet).pressed_button
        role = Role.HIGHLIGHT if pressed is not None and pressed.name == "highlight" else Role.EXCLUDE
        inverted = self.query_one("#inverted", Checkbox).value
        enabled = self.entry.enabled if self.entry is not None else True
        self.dismiss(Entry(rule, role, enabled=enabled, inverted=inverted))

    def build_rule(self) -> Rule:
        """The rule the fields describe; ``RuleError`` says what is wrong."""
        rules = {
            "message": self._message_rule,
            "severity": self._severity_rule,
            "node": self._node_rule,
            "robot": self._robot_rule,
            "location": self._location_rule,
            "time": self._time_rule,
        }
        if self.kind != "custom":
            return rules[self.kind]()
        parts = tuple(rule for rule in (make() for make in rules.values()) if not rule.is_empty)
        return CustomRule(parts)

    def _value(self, name: str) -> str:
        return self.query_one(f"#{name}", Input).value

    def _checked(self, name: str) -> bool:
        return self.query_one(f"#{name}", Checkbox).value

    def _message_rule(self) -> Rule:
        return MessageRule(
            self._value("message-text"), self._checked("message-ignore-case"), self._checked("message-regex")
        )

    def _severity_rule(self) -> Rule:
        return SeverityRule(
            frozenset(int(level) for level in MESSAGE_SEVERITIES if self._checked(f"severity-{level.name.lower()}"))
        )

    def _node_rule(self) -> Rule:
        return NodeRule(tuple(name.strip() for name in self._value("node-names").split(",") if name.strip()))

    def _robot_rule(self) -> Rule:
        return RobotRule(tuple(name.strip() for name in self._value("robot-names").split(",") if name.strip()))

    def _location_rule(self) -> Rule:
        line_text = self._value("location-line").strip()
        if line_text and not line_text.isdigit():
            raise RuleError(f"line: expected a line number, got {line_text!r}")
        return LocationRule(
            file=self._value("location-file"),
            function=self._value("location-function"),
            line=int(line_text) if line_text else None,
            regex=self._checked("location-regex"),
            ignore_case=self._checked("location-ignore-case"),
        )

    def _time_rule(self) -> Rule:
        ends = []
        for name in ("time-from", "time-to"):
            text = self._value(name).strip()
            ends.append(parse_time(text, utc=self.utc) if text else None)
        return TimeRangeRule(*ends)
