"""The status line: rows shown of total, the search, level and node toggles, counts per
severity, rate, state, source, the rules and the time format."""

from __future__ import annotations

from dataclasses import dataclass, field

from rich.text import Text
from textual.widget import Widget

from ...model.levels import MESSAGE_SEVERITIES
from ...model.text import one_line, plural
from ...sources.status import SourceStatus

_SEVERITY_LETTER = {
    10: ("D", "dim"),
    20: ("I", "green"),
    30: ("W", "yellow"),
    40: ("E", "red"),
    50: ("F", "bold white on red"),
}


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
    """One line; updating it repaints just this line (no layout, unlike ``Static``)."""

    DEFAULT_CSS = """
    StatusBar { height: 1; background: $panel; color: $foreground; padding: 0 1; }
    """

    def __init__(self, *, id: str | None = None) -> None:
        super().__init__(id=id)
        self.content = Text()

    def show_facts(self, facts: StatusFacts) -> None:
        content = render_status(facts)
        if content.plain != self.content.plain or content.spans != self.content.spans:
            self.content = content
            self.refresh()

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


def render_status(facts: StatusFacts) -> Text:
    text = Text(no_wrap=True, overflow="ellipsis")
    if facts.paused:
        text.append(" PAUSED ", style="bold black on yellow")
        text.append(f" +{facts.new_while_paused:,} new", style="yellow")
    elif facts.following:
        text.append(" FOLLOW ", style="bold black on green")
    else:
        text.append(" SCROLL ", style="bold black on cyan")
    text.append(f"  {facts.shown:,}/{facts.total:,} shown  ")
    if facts.search:
        text.append(f"{one_line(facts.search, 120)}", style="bold black on yellow")
        text.append("  ")
    if facts.toggles:
        text.append(f"{one_line(facts.toggles, 200)}", style="bold magenta")
        text.append("  ")
    for severity in MESSAGE_SEVERITIES:
        letter, style = _SEVERITY_LETTER[int(severity)]
        text.append(letter, style=style)
        text.append(f"{facts.counts.get(int(severity), 0):,} ")
    text.append(f" {facts.rate:,.0f}/s")
    for status in facts.sources:
        if status.topic:
            text.append(f"  {one_line(status.topic, 200)}", style="bold")
            text.append(f" {plural(status.publishers, 'pub')}")
        loss = status.loss_text()
        if loss:
            text.append(f"  {loss}", style="bold red")
        if status.problem:
            text.append(f"  {one_line(status.problem, 300)}", style="bold red")
        where = one_line(" ".join(part for part in (status.path, status.origin) if part), 300)
        if where:
            text.append(f" {where}" if status.topic and not loss and not status.problem else f"  {where}", style="dim")
    if facts.note:
        text.append(f"  {facts.note}", style="italic")
    if facts.time:
        text.append(f"  {facts.time}", style="italic")
    return text
