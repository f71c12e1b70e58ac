"""The summary of the run: counts per severity and per node, the busiest nodes over the
last minute, the first message of each severity, and the live sources (what they read, how,
what was lost). Every line is a jump target: Enter (or a
click) shows its message in the table.

It counts every kept message (what the rules hide too: it describes the run, like the
counts on the status line); a target the rules hide is said so instead of shown.
"""

from __future__ import annotations

from collections.abc import Sequence

from rich.text import Text
from textual.app import ComposeResult
from textual.binding import Binding
from textual.containers import Vertical
from textual.screen import ModalScreen
from textual.widgets import Label, OptionList
from textual.widgets.option_list import Option

from ...model.inert_text import one_line, plural, shorten_name
from ...model.levels import MESSAGE_SEVERITIES, severity_level
from ...model.overview.node_stats import NodeStats, robot_counts
from ...model.store.log_store import LogStore
from ...model.timefmt import clock_text, duration_text
from ...sources.status import SourceStatus
from ..keys import hint_line
from ..severity_styles import severity_classes, severity_css
from ..widgets.timeline_drawing import span_text

_NAME_WIDTH = 28
#: The dialog's room for text: its width less its border and left padding, an option's
#: padding and the scrollbar (one cell).
_FRAME = 6


class SummaryScreen(ModalScreen[int | None]):
    """The run at a glance; dismissed with the seq to show in the table, or None.

    | Key(s) | Description |
    | :- | :- |
    | enter | Show the line's message (the first of a severity, of a node) in the table. |
    | escape, q, S | Close. |

    | Class | Description |
    | :- | :- |
    | `summary--severity-debug` ... `summary--severity-fatal` | A severity's name and counts. |
    """

    DEFAULT_CSS = """
    SummaryScreen { align: center middle; }
    SummaryScreen > Vertical {
        width: 100; max-width: 96%; height: 90%; border: thick $primary; background: $surface; padding: 0 0 0 1;
    }
    SummaryScreen #summary-title { text-style: bold; width: 1fr; }
    SummaryScreen #summary-keys { color: $text-muted; width: 1fr; }
    /* Lines cut where the list ends; its scrollbar at the box's edge, one cell wide, not a
       stray mark inside the box. */
    SummaryScreen OptionList, SummaryScreen OptionList:focus {
        height: 1fr; border: none; padding: 0; text-wrap: nowrap; text-overflow: ellipsis;
        scrollbar-size-vertical: 1;
    }
    """ + severity_css("SummaryScreen", "summary--severity")
    COMPONENT_CLASSES = severity_classes("summary--severity")
    BINDINGS = [
        Binding("enter", "jump", "Show it in the table", show=False, id="summary.jump"),
        Binding("escape,q,S", "close", "Close", show=False, id="summary.close"),
    ]

    def __init__(
        self,
        store: LogStore,
        stats: NodeStats,
        shown: int,
        *,
        utc: bool = False,
        sources: Sequence[SourceStatus] = (),
    ) -> None:
        super().__init__()
        self.store = store
        self.stats = stats
        self.shown_rows = shown
        self.utc = utc
        self.sources = sources
        #: option id -> what its line jumps to
        self._targets: dict[str, str] = {}

    def compose(self) -> ComposeResult:
        with Vertical():
            yield Label(self._title(), id="summary-title")
            yield Label(Text(self._keys()), id="summary-keys")
            yield OptionList(*self._options(), id="summary-list")

    def on_mount(self) -> None:
        options = self.query_one(OptionList)
        options.focus()
        for index in range(options.option_count):
            if not options.get_option_at_index(index).disabled:
                options.highlighted = index
                break

    def _keys(self) -> str:
        return hint_line(self.app, self.BINDINGS, [("jump", "shows it in the table"), ("close", "closes")])

    def _title(self) -> Text:
        store = self.store
        text = Text(f"Summary: {len(store):,} messages kept", style="bold")
        spans = list(store.spans(store.first_seq, store.end_seq))
        if spans:
            oldest = min(min(span.chunk.stamps[span.lo : span.hi]) for span in spans)
            newest = max(max(span.chunk.stamps[span.lo : span.hi]) for span in spans)
            first, last = span_text(oldest, newest, utc=self.utc)
            text.append(f", {first} to {last} ({duration_text(newest - oldest)})")
        hidden = len(store) - self.shown_rows
        if hidden > 0:
            text.append(f"; the rules hide {hidden:,}", style="italic")
        return text

    def _room(self) -> int:
        """Cells for a line of the list: the dialog's width less its frame."""
        return max(min(100, self.app.size.width * 96 // 100) - _FRAME, 40)

    def _widths(self) -> tuple[int, int]:
        """The node column's width and a count's, to fit the dialog (narrower on 80 columns)."""
        room = self._room() - 2
        count_width = 9 if room - 6 * 9 - 1 >= _NAME_WIDTH else 8
        return max(min(room - 6 * count_width - 1, _NAME_WIDTH), 12), count_width

    def _options(self) -> list[Option]:
        store, stats = self.store, self.stats
        name_width, count_width = self._widths()
        #: The severities drawn as everywhere else (the theme's, and by weight without colour).
        styles = [
            self.get_component_rich_style(f"summary--severity-{severity_level(level).style}", partial=True)
            for level in MESSAGE_SEVERITIES
        ]
        nodes = stats.nodes()
        # A fleet: each robot's counts first, where they are seen without scrolling.
        robots = robot_counts(nodes) if any(entry.robot for entry in nodes) else {}
        options: list[Option] = []
        if robots:
            options.append(_heading(header_of("Robots", name_width, count_width)))
        for robot, numbers in robots.items():
            line = Text(f"  {_name(robot or '(no robot)', name_width):<{name_width}}")
            for slot, number in enumerate(numbers):
                line.append(f"{number:>{count_width},}", style=styles[slot] if number else "dim")
            line.append(f"{sum(numbers):>{count_width + 1},}", style="bold")
            options.append(self._target_option(line, None))
        if robots:
            options.append(_heading(""))
        options += [*self._source_options(), _heading("Severity       count   first")]
        counts = store.counts
        for slot, severity in enumerate(MESSAGE_SEVERITIES):
            number = counts.get(int(severity), 0)
            first = stats.first_of(int(severity)) if number else None
            line = Text(f"  {severity.name:<7}", style=styles[slot])
            line.append(f"{number:>11,}")
            if first is not None:
                record = store.get(first)
                line.append(f"   {clock_text(record.stamp_ns, utc=self.utc)}")
                if severity >= 40:
                    who = f"{record.robot}: {record.node}" if record.robot else record.node
                    line.append(f"  {one_line(who, 60)}: {one_line(record.msg, 200)}")
            options.append(self._target_option(line, f"seq:{first}" if first is not None else None))
        busiest = stats.busiest(5)
        options.append(_heading(""))
        options.append(_heading(f"Busiest nodes, last {stats.window_seconds()} s"))
        if not busiest:
            options.append(_heading("  none"))
        for entry in busiest:
            line = Text(f"  {_name(entry.label, name_width):<{name_width}}", style="bold")
            line.append(f"{entry.rate:>12,.1f}/s")
            options.append(self._target_option(line, f"node:{entry.node_id}"))
        options.append(_heading(""))
        options.append(_heading(header_of("Nodes", name_width, count_width)))
        for entry in nodes:
            line = Text(f"  {_name(entry.label, name_width):<{name_width}}")
            for slot, number in enumerate(entry.counts):
                line.append(f"{number:>{count_width},}", style=styles[slot] if number else "dim")
            line.append(f"{entry.total:>{count_width + 1},}", style="bold")
            options.append(self._target_option(line, f"node:{entry.node_id}"))
        return options

    def _source_options(self) -> list[Option]:
        """What each live source reads, how, and what it lost (none: nothing), each followed
        by an empty line; first in the list (after a fleet's counts per robot), where it is seen
        without scrolling."""
        options: list[Option] = []
        for status in self.sources:
            if not (status.topic or status.origin):  # no reader of a topic (the demo's nodes)
                continue
            where = f"{status.topic or '(no topic yet)'}, {plural(status.publishers, 'publisher')}"
            if status.robot:
                where = f"robot {status.robot} ({status.state}): {where}"
            options.append(_heading(f"Source: {one_line(where, 200)}"))
            if status.robot:  # a fleet's: one line each
                taken = f"taken by {status.path}" if status.path else ""
                lines = [
                    " · ".join(part for part in (status.origin, taken, f"lost: {status.loss_text() or 'none'}") if part)
                ]
                lines.append(status.problem)
            else:
                lines = self._source_lines(status)
            for line in lines:
                if line:
                    options.append(self._target_option(Text(f"  {one_line(line, 400)}"), None))
            options.append(_heading(""))
        return options

    @staticmethod
    def _source_lines(status: SourceStatus) -> list[str]:
        """What a single source reads, how, what it lost, its problem: a line each."""
        return [
            status.origin,
            f"taken by {status.path_text()}" if status.path else "",
            (
                f"{status.loop_name()}: {status.path_note}"
                if status.path in ("c+cdr", "c+tcpros")
                else f"{status.loop_name()} is not used: {status.path_note}"
            )
            if status.path_note
            else "",
            f"lost: {status.loss_text() or 'none known'}",
            f"{status.decoded_by_rclpy:,} read by rclpy (the direct decoder refused them)"
            if status.decoded_by_rclpy
            else "",
            status.problem,
        ]

    def _target_option(self, line: Text, target: str | None) -> Option:
        """A line that jumps to ``target`` (``seq:N``, ``node:ID``); none: a line only. The
        list cuts it where its width ends (its CSS: one line each, ``…`` at the end)."""
        if target is None:
            return Option(line, disabled=True)
        option_id = f"line-{len(self._targets)}"
        self._targets[option_id] = target
        return Option(line, id=option_id)

    def target(self, option_id: str | None) -> int | None:
        """The seq an option's line jumps to."""
        target = self._targets.get(option_id or "")
        if not target:
            return None
        kind, _, value = target.partition(":")
        if kind == "seq":
            return int(value)
        if kind == "node":
            return self.stats.first_of_node(int(value))
        return None

    def on_option_list_option_selected(self, event: OptionList.OptionSelected) -> None:
        self.dismiss(self.target(event.option.id))

    def action_jump(self) -> None:
        options = self.query_one(OptionList)
        if options.highlighted is not None:
            options.action_select()

    def action_close(self) -> None:
        self.dismiss(None)


def _name(node: str, width: int) -> str:
    """A node's name in ``width`` cells, shortened as the table does (its end kept: that is
    what tells ``navigation.planner`` from ``navigation.planner.costmap``)."""
    return shorten_name(one_line(node, 200), width)


def header_of(title: str, name_width: int, count_width: int) -> str:
    """A table's heading: its title, the severities' names, ``total``."""
    return (
        f"{title:<{name_width + 2}}"
        + "".join(f"{s.name:>{count_width}}" for s in MESSAGE_SEVERITIES)
        + f"{'total':>{count_width + 1}}"
    )


def _heading(text: str) -> Option:
    return Option(Text(text, style="bold underline" if text and not text.startswith(" ") else "dim"), disabled=True)
