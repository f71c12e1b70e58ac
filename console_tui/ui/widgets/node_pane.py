"""The node panel, beside the table: every node (logger) seen, its messages per severity and
its rate (over the last minute of stamps); solo or mute a node with one key.

It shares the right side with the logger levels pane (opening one closes the other). The
counts are the model's ``NodeStats`` (of the messages kept, whatever the rules show), brought
up to date and read again every second while the panel is open: what arrived while it was
closed is counted then, ``COUNT_BUDGET_S`` at a time (the title says "counting" until it is
done); solo and mute are rules (``model/rules/key_rules.py``), which the app applies when the panel
asks (``Toggle``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from rich.console import Console, ConsoleOptions, RenderResult
from rich.measure import Measurement
from rich.style import Style
from rich.table import Table
from rich.text import Text
from textual import on
from textual.app import ComposeResult
from textual.binding import Binding
from textual.message import Message
from textual.timer import Timer
from textual.widget import Widget
from textual.widgets import Input, OptionList, Static
from textual.widgets.option_list import Option

from ...model.inert_text import one_line, shorten_name
from ...model.levels import SEVERITY_TABLE
from ...model.loggers.logger_levels import robot_qualified
from ...model.overview.node_stats import NodeCounts, NodeStats
from ..focus import focus_now
from ..keys import Hint, hint_line
from ..severity_styles import severity_classes, severity_css
from .side_pane import RightPane

REFRESH_S = 1.0
#: How long one refresh counts records for, and how soon the next comes while some are left
#: (opened over a million messages kept, the counts are complete in about a second).
COUNT_BUDGET_S = 0.015
CATCH_UP_S = 0.05

_HINTS: list[Hint] = [
    ("solo", "solo"),
    ("mute", "mute"),
    ("clear_toggles", "hear all"),
    ("sort", "sort"),
    ("filter", "filter"),
    ("leave", "table"),
]


@dataclass(frozen=True)
class Sort:
    key: str
    title: str
    order: Callable[[NodeCounts], Any]


def _errors(row: NodeCounts) -> int:
    return row.counts[3] + row.counts[4]


SORTS = (
    Sort("name", "name", lambda row: (row.robot, row.node)),
    Sort("errors", "errors", lambda row: (-_errors(row), -row.counts[2], row.robot, row.node)),
    Sort("warnings", "warnings", lambda row: (-row.counts[2], -_errors(row), row.robot, row.node)),
    Sort("total", "messages", lambda row: (-row.total, row.robot, row.node)),
    Sort("rate", "rate", lambda row: (-row.rate, row.robot, row.node)),
)

_PLAIN = Style()


def compact(number: int) -> str:
    """Short: ``9999``, ``12k``, ``1.2M`` (4 characters at most below 10 million)."""
    if number < 10_000:
        return str(number)
    if number < 999_500:
        return f"{number / 1000:.0f}k"
    return f"{number / 1_000_000:.1f}M"


def rate_cell(rate: float) -> str:
    if rate < 100:
        return f"{rate:.1f}"
    return compact(round(rate))


#: Widths of the count columns (D, I, W, E, F) and of the rate, when no rows say otherwise.
_NARROWEST = (4, 4, 4, 4, 4, 5)


def column_widths(rows: Sequence[NodeCounts]) -> tuple[int, ...]:
    """Each count column as wide as its widest number (its title and a space at least), and
    the rate's: the names get the rest of a narrow pane."""
    widths = list(_NARROWEST)
    for row in rows:
        for at, count in enumerate(row.counts):
            widths[at] = max(widths[at], len(compact(count)) + 1)
        widths[5] = max(widths[5], len(rate_cell(row.rate)) + 1)
    return tuple(widths)


class NodeName:
    """A node's name in the width its column gets, shortened as the table shortens it: its end
    kept (``/na…/planner``), which tells ``/navigation/planner`` from ``/navigation/planning``."""

    def __init__(self, name: str, style: str = "") -> None:
        self.name = name
        self.style = style

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> RenderResult:
        yield Text(shorten_name(self.name, options.max_width), style=self.style, no_wrap=True)

    def __rich_measure__(self, console: Console, options: ConsoleOptions) -> Measurement:
        return Measurement(1, len(self.name))


def _grid(widths: Sequence[int]) -> Table:
    grid = Table.grid(expand=True)
    grid.add_column(width=2, no_wrap=True)
    grid.add_column(ratio=1, no_wrap=True, overflow="ellipsis")
    for width in widths:
        grid.add_column(width=width, justify="right", no_wrap=True)
    return grid


def node_line(
    row: NodeCounts, state: str, widths: Sequence[int] = _NARROWEST, styles: Mapping[str, Style] | None = None
) -> Table:
    """A node's line: S (solo) or M (mute), its name, its counts per severity, its rate;
    ``styles`` are the pane's component classes."""

    def look(name: str) -> Style:
        return (styles or {}).get(f"node-pane--{name}", _PLAIN)

    grid = _grid(widths)
    name_style = "dim strike" if state == "M" else "bold" if state == "S" else ""
    counts = [
        Text(compact(count), style=look(f"severity-{level.style}" if count else "none"))
        for count, level in zip(row.counts, SEVERITY_TABLE, strict=True)
    ]
    grid.add_row(
        Text(state, style="bold reverse" if state else ""),
        NodeName(one_line(row.label, 200), name_style),
        *counts,
        Text(rate_cell(row.rate), style=look("rate")),
    )
    return grid


def header_line(sort: Sort, widths: Sequence[int] = _NARROWEST) -> Table:
    grid = _grid(widths)
    titles = {"name": "node", "errors": "E", "warnings": "W", "rate": "/s"}
    arrow = {key: f"{title}▼" if key == sort.key and key != "name" else title for key, title in titles.items()}
    name = "node ▲" if sort.key == "name" else "node"
    if sort.key == "total":
        name += "  (by messages ▼)"
    letters = {level.letter: level.letter for level in SEVERITY_TABLE} | {"W": arrow["warnings"], "E": arrow["errors"]}
    grid.add_row("", name, *letters.values(), arrow["rate"])
    return grid


class NodeCountList(OptionList):
    """The nodes, a line each with its counts and rate; ``s``, ``m`` act on the highlighted one."""


class NodePane(RightPane):
    """Every node seen, its counts and rate; solo / mute with one key.

    | Key(s) | Description |
    | :- | :- |
    | s, enter | Solo the highlighted node (again: take it out of the solo). |
    | m | Mute it (again: hear it). |
    | x | Every node heard again: no solo, no mute. |
    | o | Sort by name, errors, warnings, messages, rate. |
    | slash | The filter box. |
    | escape | Back to the table. |

    | Class | Description |
    | :- | :- |
    | `node-pane--severity-debug` ... `node-pane--severity-fatal` | A node's count of a severity. |
    | `node-pane--none` | A count of none. |
    | `node-pane--rate` | A node's messages per second. |
    """

    COMPONENT_CLASSES = {*severity_classes("node-pane--severity"), "node-pane--none", "node-pane--rate"}

    DEFAULT_CSS = """
    NodePane > .node-pane--none { color: $foreground-muted; text-style: dim; }
    NodePane > .node-pane--rate { color: $text-primary; }
    NodePane {
        width: 56;
        max-width: 55%;
        & > #nodes-header { height: 1; color: $text-muted; text-style: bold; }
        & > NodeCountList { height: 1fr; }
        & > NodeCountList:focus { background-tint: $foreground 5%; }
    }
    """ + severity_css("NodePane", "node-pane--severity")

    BINDINGS = [
        Binding("s,enter", "solo", "Solo the node", show=False, id="nodes.solo"),
        Binding("m", "mute", "Mute the node", show=False, id="nodes.mute"),
        Binding("x", "clear_toggles", "Every node heard again", show=False, id="nodes.clear"),
        Binding("o", "sort", "Sort by name, errors, warnings, messages, rate", show=False, id="nodes.sort"),
        Binding("slash", "filter", "Filter the nodes by name", show=False, id="nodes.filter"),
        Binding("escape", "leave", "Back to the table", show=False, id="nodes.leave"),
    ]

    @dataclass
    class Toggle(Message):
        """Solo or mute ``node`` (``kind`` "solo", "mute"), or no solo and no mute ("clear")."""

        kind: str
        node: str = ""

    def __init__(
        self,
        stats: NodeStats,
        toggles: Callable[[], tuple[tuple[str, ...], tuple[str, ...]]],
        *,
        id: str | None = "node-pane",
    ) -> None:
        super().__init__(id=id)
        self.stats = stats
        #: The nodes soloed and muted now (the app's rules).
        self.toggles = toggles
        self.sort = SORTS[1]
        self.filter_text = ""
        self.rows: list[NodeCounts] = []
        self._option_nodes: dict[str, str] = {}
        self._shown_key: tuple = ()
        self._timer: Timer | None = None
        #: Records kept are still being counted (the panel opened over many not counted yet).
        self.counting = False
        self.node_list = NodeCountList(id="nodes-list", compact=True)
        self.filter_input = Input(placeholder="filter nodes: part of a name", id="nodes-filter", compact=True)

    def compose(self) -> ComposeResult:
        yield Static("Nodes", id="nodes-title", classes="pane-title")
        yield self.filter_input
        yield Static(header_line(self.sort), id="nodes-header")
        yield self.node_list
        yield Static(hint_line(self.app, self.BINDINGS, _HINTS), id="nodes-keys", classes="pane-keys")

    def focus_target(self) -> Widget:
        return self.node_list

    def when_opened(self) -> None:
        self.update_counts()

    def when_closed(self) -> None:
        if self._timer is not None:
            self._timer.stop()
            self._timer = None

    # -- counts ---------------------------------------------------------------------------------

    def update_counts(self) -> None:
        """Read the counts again and show them."""
        if not self.is_open:
            return
        self.counting = not self.stats.sync(COUNT_BUDGET_S)
        self.rows = self.stats.nodes()
        self.show()
        if self._timer is not None:
            self._timer.stop()
        self._timer = self.set_timer(CATCH_UP_S if self.counting else REFRESH_S, self.update_counts)

    def show(self) -> None:
        """The rows as they are now, filtered and sorted, with the solo and mute marks."""
        soloed, muted = self.toggles()
        needle = self.filter_text.casefold()
        rows = [row for row in self.rows if needle in row.label.casefold()] if needle else list(self.rows)
        rows.sort(key=self.sort.order)
        states = {name: "S" for name in soloed} | {name: "M" for name in muted}
        key = (tuple(rows), tuple(sorted(states.items())), self.sort.key)
        title = self.query_one("#nodes-title", Static)
        parts = [f"Nodes: {len(self.rows)}"]
        if needle:
            parts.append(f"{len(rows)} shown")
        if soloed:
            parts.append(f"solo {len(soloed)}")
        if muted:
            parts.append(f"muted {len(muted)}")
        if self.counting:
            parts.append("counting…")
        title.update(" · ".join(parts))
        if key == self._shown_key:
            return
        self._shown_key = key
        widths = column_widths(rows)
        self.query_one("#nodes-header", Static).update(header_line(self.sort, widths))
        options = self.node_list
        highlighted = self.highlighted_option_id
        with options.prevent(OptionList.OptionHighlighted):
            options.clear_options()
            styles = {name: self.get_component_rich_style(name, partial=True) for name in self.COMPONENT_CLASSES}
            # A robot's node is one option (the same node name on two robots is two).
            self._option_nodes = {row.label: robot_qualified(row.robot, row.node) for row in rows}
            options.add_options(
                [
                    Option(
                        node_line(row, states.get(robot_qualified(row.robot, row.node), ""), widths, styles),
                        id=row.label,
                    )
                    for row in rows
                ]
            )
            if rows:
                ids = [row.label for row in rows]
                options.highlighted = ids.index(highlighted) if highlighted in ids else 0

    @property
    def highlighted_option_id(self) -> str | None:
        option = self.node_list.highlighted_option
        return None if option is None else option.id

    @property
    def highlighted_node(self) -> str | None:
        """The node of the highlighted row as solo and mute name it (in a fleet ``ROBOT:/node``:
        that robot's node only)."""
        option = self.highlighted_option_id
        return None if option is None else self._option_nodes.get(option, option)

    # -- keys ---------------------------------------------------------------------------------

    def action_solo(self) -> None:
        node = self.highlighted_node
        if node is not None:
            self.post_message(self.Toggle("solo", node))

    def action_mute(self) -> None:
        node = self.highlighted_node
        if node is not None:
            self.post_message(self.Toggle("mute", node))

    def action_clear_toggles(self) -> None:
        self.post_message(self.Toggle("clear"))

    def action_sort(self) -> None:
        self.sort = SORTS[(SORTS.index(self.sort) + 1) % len(SORTS)]
        self.show()

    def action_filter(self) -> None:
        focus_now(self.filter_input)

    @on(OptionList.OptionSelected, "#nodes-list")
    def _selected(self, event: OptionList.OptionSelected) -> None:
        event.stop()
        self.action_solo()

    @on(Input.Changed, "#nodes-filter")
    def _filter_changed(self, event: Input.Changed) -> None:
        event.stop()
        self.filter_text = event.value.strip()
        self.show()

    @on(Input.Submitted, "#nodes-filter")
    def _filter_submitted(self, event: Input.Submitted) -> None:
        event.stop()
        focus_now(self.node_list)
