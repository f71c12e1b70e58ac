"""The status line: the state (follow, scroll, paused), rows shown of total, the search, level
and node toggles, counts per severity, rate, the sources, the rules and storms, the time format."""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

from rich.style import Style
from rich.text import Text
from textual.reactive import reactive
from textual.widget import Widget

from ...model.inert_text import one_line, plural
from ...model.levels import SEVERITY_TABLE
from ...model.store.history_status import HistoryState
from ...sources.status import SourceStatus
from ..severity_styles import severity_classes, severity_css
from .status_fit import COUNTS, DEMO, DETAIL, RATE, SOURCE, STATE, WHERE, Part, fit


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
    #: Records dropped at the bound, the history kept in memory (a full disk), or None.
    history: HistoryState | None = None


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
    | `status-bar--problem` | Losses, a source's problem, a history that cannot go to disk. |
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
        self._facts: StatusFacts | None = None

    def show_facts(self, facts: StatusFacts) -> None:
        """Redrawn only when what it says (or how) changed: ``content`` compares text and spans."""
        self._facts = facts
        width = self.content_region.width or None  # not laid out yet: everything, in full
        self.content = render_status(facts, self.component_styles(), width)

    def on_resize(self) -> None:
        if self._facts is not None:
            self.show_facts(self._facts)

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
    robots = [status for status in facts.sources if status.robot]
    if len(robots) > 1:  # a fleet: each robot's state in a word
        states = ", ".join(f"{one_line(status.robot, 32)} {status.state}" for status in robots)
        return f"waiting for the robots' messages: {states}…"
    for status in facts.sources:
        where = f" on {one_line(status.origin, 120)}" if status.origin else ""
        # No topic yet: the source takes /rosout_agg when something publishes it, else /rosout.
        topic = one_line(status.topic, 120) or "/rosout or /rosout_agg"
        if status.problem:
            return one_line(status.problem, 300)
        if status.hint:  # a source of no ROS topic says what it waits for
            return one_line(status.hint, 300)
        if status.path == "starting":
            return f"starting{where}…"
        if not status.publishers:
            return f"waiting for {topic} publishers{where}…"
        return f"{plural(status.publishers, 'publisher')} of {topic}{where}: waiting for the first message…"
    return ""


def render_status(facts: StatusFacts, styles: Mapping[str, Style] | None = None, width: int | None = None) -> Text:
    """The status line's text; ``styles`` are the component classes' (plain text without them).
    In ``width`` cells, the less important parts shortened first, then left out (``status_fit``)."""
    look = (lambda name: styles.get(f"status-bar--{name}", _PLAIN)) if styles else (lambda name: _PLAIN)

    def styled(*spans: tuple[str, str | None]) -> Text:
        return Text.assemble(*((text, look(style) if style else _PLAIN) for text, style in spans))

    parts: list[Part] = []
    if facts.paused:
        new = f" +{facts.new_while_paused:,} new"
        parts.append(Part(styled((" PAUSED ", "paused"), (new, "severity-warn")), STATE, gap=""))
    else:
        state = " FOLLOW " if facts.following else " SCROLL "
        parts.append(Part(styled((state, "follow" if facts.following else "scroll")), STATE, gap=""))
    shown = f"{facts.shown:,}/{facts.total:,}"
    parts.append(Part(Text(f"{shown} shown"), COUNTS, Text(shown)))
    if facts.search:
        search = one_line(facts.search, 120)
        parts.append(Part(styled((search, "search")), SOURCE, styled((one_line(search, 24), "search"))))
    if facts.toggles:
        toggles = one_line(facts.toggles, 200)
        parts.append(Part(styled((toggles, "toggles")), WHERE, styled((one_line(toggles, 24), "toggles"))))
    counts = [
        (f"{level.letter}{facts.counts.get(int(level.severity), 0):,}", f"severity-{level.style}")
        for level in SEVERITY_TABLE
    ]
    spaced = [span for count in counts for span in (count, (" ", None))][:-1]
    worse = [span for count in counts[2:] for span in (count, (" ", None))][:-1]  # WARN and worse
    parts.append(Part(styled(*spaced), COUNTS, styled(*worse)))
    parts.append(Part(Text(f"{facts.rate:,.0f}/s"), RATE))
    if facts.history is not None:
        history = facts.history
        style = "problem" if history.problem else "where"
        priority = SOURCE if history.problem else WHERE
        parts.append(Part(styled((history.text, style)), priority, styled((history.short, style))))
    robots = [status for status in facts.sources if status.robot]
    if len(robots) > 1:  # a fleet: each robot's state in a mark
        parts += _fleet_parts(robots, styled)
    for status in facts.sources if len(robots) <= 1 else [s for s in facts.sources if not s.robot]:
        parts += _source_parts(status, styled)
    if facts.note:
        parts.append(Part(styled((facts.note, "note")), DETAIL, styled((one_line(facts.note, 24), "note"))))
    if facts.time:
        parts.append(Part(styled((facts.time, "note")), DEMO))
    return fit(parts, width)


def _source_parts(status: SourceStatus, styled: Callable[..., Text]) -> list[Part]:
    """A source's parts: its topic and publishers, losses and problem (which matter most),
    where it reads (ROS 2's domain, ROS 1's master), why this ROS, then how (``c+cdr``)."""
    parts: list[Part] = []
    if status.topic:
        topic = one_line(status.topic, 200)
        publishers = plural(status.publishers, "pub")
        short = styled((one_line(topic, 24), "topic"), (f" {status.publishers}p", None))
        parts.append(Part(styled((topic, "topic"), (f" {publishers}", None)), SOURCE, short))
    loss = status.loss_text()
    if loss:
        parts.append(Part(styled((loss, "problem")), SOURCE, styled((f"{status.lost:,} lost", "problem"))))
    if status.problem:
        problem = one_line(status.problem, 300)
        parts.append(Part(styled((problem, "problem")), STATE, styled((short_problem(problem), "problem"))))
    if status.origin:
        origin = one_line(status.origin, 300)
        parts.append(Part(styled((origin, "where")), WHERE, styled((_short_origin(origin), "where"))))
    if status.remark:
        remark = one_line(status.remark, 300)
        brief = remark.split(" at ", 1)[0] + " (--ros1 waits)" if "(--ros1" in remark else one_line(remark, 40)
        parts.append(Part(styled((remark, "where")), WHERE, styled((brief, "where"))))
    if status.path:
        path = one_line(status.path, 200)
        demo = path.startswith("demo")
        # How messages are taken, and what a log warehouse has read, are details; a demo's and
        # a file's are where it reads.
        priority = DETAIL if status.take_path or status.path_is_progress else DEMO if demo else WHERE
        parts.append(Part(styled((path, "where")), priority, styled(("demo", "where")) if demo else None))
    return parts


#: An address in a problem's text (``http://host:11311``, up to a ``: `` or a space after it).
_ADDRESS = re.compile(r" (?:at|from|to) [a-z][a-z0-9+.-]*://[^\s]*?(?=:\s|\s|$)")


def short_problem(problem: str) -> str:
    """A source's problem in 40 cells, for a narrow status line: without the addresses it
    names (the line says where the source reads), so that what is wrong fits, not the address
    ("waiting for master: connection refused…" instead of "waiting for master at http://1…")."""
    brief = _ADDRESS.sub("", one_line(problem, 300))
    return brief if len(brief) <= 40 else brief[:39] + "…"


def _short_origin(origin: str) -> str:
    """``ROS 2 domain 11`` as ``domain 11``; ``ROS 1 http://robot:11311/`` as ``ROS 1 robot:11311``;
    anything else (a command ``run`` runs) in 32 cells."""
    if origin.startswith("ROS 2 domain "):
        return origin.removeprefix("ROS 2 ")
    short = origin.replace("http://", "").rstrip("/")
    if len(short) <= 32:
        return short
    # a log warehouse's long address: its end (the table); a command run: its start
    return "…" + short[-31:] if "://" in short else short[:31] + "…"


#: A fleet's robot's state in one mark (``SourceStatus.state``): the status line's legend.
STATE_MARKS = {"receiving": "✓", "waiting": "…", "starting": "…", "problem": "✗"}


def _fleet_parts(robots: list[SourceStatus], styled: Callable[..., Text]) -> list[Part]:
    """A fleet's robots, each with its state in a mark (✓ receiving, … waiting, ✗ a problem):
    ``picker✓ cart… arm✗`` (short: ``✓1/3 arm✗``), then what all of them lost. The summary
    (``S``) says more."""
    spans: list[tuple[str, str | None]] = []
    for status in robots:
        state = status.state
        style = "problem" if state == "problem" else "where" if state != "receiving" else None
        spans.append((f"{' ' if spans else ''}{one_line(status.robot, 32)}{STATE_MARKS[state]}", style))
    receiving = sum(status.state == "receiving" for status in robots)
    troubled = [(f" {one_line(s.robot, 32)}{STATE_MARKS['problem']}", "problem") for s in robots if s.problem]
    parts = [Part(styled(*spans), SOURCE, styled((f"✓{receiving}/{len(robots)}", None), *troubled))]
    # What the app's queue dropped is in every robot's lost_queue (they share the queue): once.
    lost = sum(status.lost - status.lost_queue for status in robots) + max(status.lost_queue for status in robots)
    if lost:
        parts.append(Part(styled((f"{lost:,} lost", "problem")), SOURCE))
    return parts


_PLAIN = Style()
