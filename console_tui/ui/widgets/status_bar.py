"""The status line: the state (follow, scroll, paused), rows shown of total, the search, level
and node toggles, counts per severity, rate, the sources, the rules and storms, the time format."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from rich.style import Style
from rich.text import Text
from textual.reactive import reactive
from textual.widget import Widget

from ...model.levels import SEVERITY_TABLE
from ...model.text import one_line, plural
from ...sources.status import SourceStatus
from ..severity_styles import severity_classes, severity_css


@dataclass
class StatusFacts:
    """Everything the status line shows; the app fills it each tick."""

    shown: int = 0
    total: int = 0
    counts: dict[int, int] = field(default_factory=dict)
    rate: float = 0.0
    following: bool = True
    paused: bool = False
    new_while_paused: int = 0
    sources: list[SourceStatus] = field(default_factory=list)
    note: str = ""
    #: The search: ``match 3 of 17 'timeout'``, or "".
    search: str = ""
    #: Level and node toggles in force: ``level≥WARN · solo navigation.planner``, or "".
    toggles: str = ""
    #: What the Time column shows when not the wall clock, and a sim time note, or "".
    time: str = ""


class StatusBar(Widget):
    """One line; updating it repaints just this line (no layout, unlike ``Static``).

    | Class | Description |
    | :- | :- |
    | `status-bar--follow` | FOLLOW: the table follows the newest message. |
    | `status-bar--scroll` | SCROLL: the table stays where the user put it. |
    | `status-bar--paused` | PAUSED (the count of messages that came since is drawn as WARN's). |
    | `status-bar--search` | The search and where the cursor is among its matches. |
    | `status-bar--toggles` | The level and node toggles in force. |
    | `status-bar--severity-debug` ... `status-bar--severity-fatal` | A severity's count. |
    | `status-bar--topic` | The live topic. |
    | `status-bar--problem` | Losses and a source's problem. |
    | `status-bar--where` | Where records come from (a file, a log folder). |
    | `status-bar--note` | What the rules and storms do; the time format. |
    """

    DEFAULT_CSS = """
    StatusBar { height: 1; background: $panel; color: $foreground; padding: 0 1; }
    StatusBar > .status-bar--follow { background: $success; color: $text; text-style: bold; }
    StatusBar > .status-bar--scroll { background: $primary; color: $text; text-style: bold; }
    StatusBar > .status-bar--paused { background: $warning; color: $text; text-style: bold; }
    StatusBar > .status-bar--search { background: $accent; color: $text; text-style: bold; }
    StatusBar > .status-bar--toggles { color: $text-accent; text-style: bold; }
    StatusBar > .status-bar--topic { text-style: bold; }
    StatusBar > .status-bar--problem { color: $text-error; text-style: bold; }
    StatusBar > .status-bar--where { color: $foreground-muted; }
    StatusBar > .status-bar--note { text-style: italic; }
    StatusBar:nocolor > .status-bar--follow { background: $foreground; color: $background; }
    StatusBar:nocolor > .status-bar--scroll { background: $foreground; color: $background; }
    StatusBar:nocolor > .status-bar--paused { background: $foreground; color: $background; }
    StatusBar:nocolor > .status-bar--search { background: $foreground; color: $background; }
    StatusBar:nocolor > .status-bar--toggles { color: $foreground; }
    StatusBar:nocolor > .status-bar--problem { color: $foreground; text-style: bold underline; }
    """ + severity_css("StatusBar", "status-bar--severity")

    COMPONENT_CLASSES = {
        "status-bar--follow",
        "status-bar--scroll",
        "status-bar--paused",
        "status-bar--search",
        "status-bar--toggles",
        *severity_classes("status-bar--severity"),
        "status-bar--topic",
        "status-bar--problem",
        "status-bar--where",
        "status-bar--note",
    }

    content: reactive[Text] = reactive(Text, layout=False)

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self._styles: dict[str, Style] = {}
        self._styles_key: object = None

    def show_facts(self, facts: StatusFacts) -> None:
        """Redrawn only when what it says (or how) changed: ``content`` compares text and spans."""
        self.content = render_status(facts, self.component_styles())

    def component_styles(self) -> dict[str, Style]:
        """The component classes' styles, looked up again when the theme changes."""
        key = self.app.theme
        if key != self._styles_key or not self._styles:
            self._styles_key = key
            self._styles = {name: self.get_component_rich_style(name, partial=True) for name in self.COMPONENT_CLASSES}
        return self._styles

    def notify_style_update(self) -> None:
        super().notify_style_update()
        self._styles = {}

    def render(self) -> Text:
        return self.content


def empty_hint(facts: StatusFacts, filtering: bool = False) -> str:
    """What the table says while it shows no row: what the console is waiting for, or that
    rules hide every message; "" when rows are shown (or paused: the status says so)."""
    if facts.shown or facts.paused:
        return ""
    if facts.total:
        if filtering:
            return "filtering…"
        return f"nothing matches: {plural(facts.total, 'message')} hidden by rules"
    for status in facts.sources:
        where = f" on {one_line(status.origin, 120)}" if status.origin else ""
        # No topic yet: the source takes /rosout_agg when something publishes it, else /rosout.
        topic = one_line(status.topic, 120) or "/rosout or /rosout_agg"
        if status.problem:
            return one_line(status.problem, 300)
        if status.path == "starting":
            return f"starting{where}…"
        if not status.publishers:
            return f"waiting for {topic} publishers{where}…"
        return f"{plural(status.publishers, 'publisher')} of {topic}{where}: waiting for the first message…"
    return ""


def render_status(facts: StatusFacts, styles: Mapping[str, Style] | None = None) -> Text:
    """The status line's text; ``styles`` are the component classes' (plain text without them)."""
    look = (lambda name: styles.get(f"status-bar--{name}", _PLAIN)) if styles else (lambda name: _PLAIN)
    text = Text(no_wrap=True, overflow="ellipsis")
    if facts.paused:
        text.append(" PAUSED ", style=look("paused"))
        text.append(f" +{facts.new_while_paused:,} new", style=look("severity-warn"))
    elif facts.following:
        text.append(" FOLLOW ", style=look("follow"))
    else:
        text.append(" SCROLL ", style=look("scroll"))
    text.append(f"  {facts.shown:,}/{facts.total:,} shown  ")
    if facts.search:
        text.append(f"{one_line(facts.search, 120)}", style=look("search"))
        text.append("  ")
    if facts.toggles:
        text.append(f"{one_line(facts.toggles, 200)}", style=look("toggles"))
        text.append("  ")
    for level in SEVERITY_TABLE:
        text.append(
            f"{level.letter}{facts.counts.get(int(level.severity), 0):,}", style=look(f"severity-{level.style}")
        )
        text.append(" ")
    text.append(f" {facts.rate:,.0f}/s")
    for status in facts.sources:
        if status.topic:
            text.append(f"  {one_line(status.topic, 200)}", style=look("topic"))
            text.append(f" {plural(status.publishers, 'pub')}")
        loss = status.loss_text()
        if loss:
            text.append(f"  {loss}", style=look("problem"))
        if status.problem:
            text.append(f"  {one_line(status.problem, 300)}", style=look("problem"))
        where = one_line(" ".join(part for part in (status.path, status.origin) if part), 300)
        if where:
            spaced = f" {where}" if status.topic and not loss and not status.problem else f"  {where}"
            text.append(spaced, style=look("where"))
    if facts.note:
        text.append(f"  {facts.note}", style=look("note"))
    if facts.time:
        text.append(f"  {facts.time}", style=look("note"))
    return text


_PLAIN = Style()
