"""The timeline strip above the table: the message rate over the whole history, by severity.

Four lines, drawn with the line API from ``Timeline.columns`` (the model does the counting):

- the time span, the duration of a column and the peak rate (or, on a picked column, its
  time and counts);
- two lines of bars, 16 steps high, the severities stacked in their colours (DEBUG at the
  bottom, FATAL on top; a cell holding several shows the worst of them);
- a line that reads without colour: ``F`` ``E`` ``W`` under columns with a FATAL, an ERROR,
  a WARN message, and the table's place in the history as ``━`` on the axis ``─``.

A click on a column, or Enter on the column picked with the arrows while the strip has the
focus, asks the app to show that time in the table (``Jump``).

Textual's ``Sparkline`` draws one series in a colour gradient by value, and plotext (through
``textual-plotext``) took about 80 ms to build a stacked bar chart of 100 columns here, too
slow to redraw while following 10,000 messages a second; ``benchmarks/timeline.py``
measures both against this strip.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from functools import lru_cache

from rich.segment import Segment
from rich.style import Style
from textual import events
from textual.binding import Binding
from textual.message import Message
from textual.strip import Strip
from textual.widget import Widget

from ...model.timefmt import clock_text, duration_text
from ...model.timeline import Timeline, TimelineColumns

#: Eighths of a cell, bottom up.
_LOWER = " ▁▂▃▄▅▆▇█"
_BAR_ROWS = 2
_EIGHTHS = 8 * _BAR_ROWS
_SEVERITIES = ("debug", "info", "warn", "error", "fatal")
_MARKS = ((4, "F"), (3, "E"), (2, "W"))
_NS_PER_S = 1_000_000_000
LINES = 4


def stack(counts: Sequence[int], peak: int, eighths: int = _EIGHTHS) -> tuple[int, ...]:
    """Eighths of the bar for each severity: the bar as high as the total against ``peak``
    (at least one eighth when there is anything), each severity its share of it, and at least
    one eighth for any WARN, ERROR or FATAL."""
    total = sum(counts)
    if not total or peak <= 0:
        return (0,) * len(counts)
    height = max((total * eighths * 2 + peak) // (2 * peak), 1)
    if total in counts:  # one severity only (the common case)
        return tuple(height if count else 0 for count in counts)
    parts = [count * height / total for count in counts]
    shares = [int(part) for part in parts]
    for slot in range(2, len(counts)):
        if counts[slot] and not shares[slot]:
            shares[slot] = 1
    short = height - sum(shares)
    order = sorted(range(len(counts)), key=lambda s: parts[s] - int(parts[s]), reverse=True)
    for slot in order:
        if short <= 0:
            break
        if counts[slot]:
            shares[slot] += 1
            short -= 1
    while short < 0:  # the minimum eighths made it too high: take from the biggest share
        biggest = max(range(len(counts)), key=lambda s: shares[s])
        if shares[biggest] <= 1:
            break
        shares[biggest] -= 1
        short += 1
    return tuple(shares)


@lru_cache(maxsize=4096)
def bar_cells(shares: tuple[int, ...]) -> tuple[tuple[str, int | None, int | None], ...]:
    """The bar's cells, bottom up: (glyph, severity slot drawn, slot behind it or None)."""
    fill: list[int] = []
    for slot, share in enumerate(shares):
        fill.extend([slot] * share)
    fill = fill[:_EIGHTHS]
    cells: list[tuple[str, int | None, int | None]] = []
    for row in range(_BAR_ROWS):
        part = fill[row * 8 : row * 8 + 8]
        if not part:
            cells.append((" ", None, None))
        elif len(part) < 8:
            cells.append((_LOWER[len(part)], max(part), None))
        elif part[0] == part[-1]:
            cells.append(("█", part[0], None))
        else:
            top = part[-1]
            below = [slot for slot in part if slot != top]
            cells.append((_LOWER[len(below)], max(below), top))
    return tuple(cells)


def span_text(start_ns: int, end_ns: int, *, utc: bool) -> tuple[str, str]:
    """The strip's first and last time, as precise as the span needs."""
    span = end_ns - start_ns
    digits = 3 if span < 60 * _NS_PER_S else 0
    if span >= 86_400 * _NS_PER_S:
        return _dated(start_ns, utc), _dated(end_ns, utc)
    return clock_text(start_ns, utc=utc, digits=digits), clock_text(end_ns, utc=utc, digits=digits)


def _dated(stamp_ns: int, utc: bool) -> str:
    seconds = stamp_ns // _NS_PER_S
    try:
        parts = time.gmtime(seconds) if utc else time.localtime(seconds)
    except (OverflowError, OSError, ValueError):
        return str(seconds)
    return time.strftime("%Y-%m-%d %H:%M", parts)


def _runs(cells: Sequence[tuple[str, Style]]) -> list[Segment]:
    """Cells as segments, neighbours of the same style joined."""
    segments: list[Segment] = []
    text: list[str] = []
    current: Style | None = None
    for glyph, style in cells:
        if style is not current and style != current:
            if text:
                segments.append(Segment("".join(text), current))
            text, current = [], style
        text.append(glyph)
    if text:
        segments.append(Segment("".join(text), current))
    return segments


def rate_text(rate: float) -> str:
    if rate >= 10_000:
        return f"{rate / 1000:,.0f}k/s"
    if rate >= 10:
        return f"{rate:,.0f}/s"
    return f"{rate:.2g}/s"


class TimelineStrip(Widget, can_focus=True):
    """The rate of the rows shown over the whole history (``Timeline``), with the table's place in it.

    | Key(s) | Description |
    | :- | :- |
    | left / right | The column before / after. |
    | shift+left, pageup / shift+right, pagedown | Ten columns earlier / later. |
    | home / end | The first / last column. |
    | enter | Show the column's time in the table (``Jump``). |
    | escape | Back to the table (``Leave``). |

    | Class | Description |
    | :- | :- |
    | `timeline--debug` .. `timeline--fatal` | A severity's part of the bars, and its mark. |
    | `timeline--label` | The first line: the span, a column's duration, the peak rate. |
    | `timeline--axis` | The axis under the bars. |
    | `timeline--position` | The table's place on the axis. |
    | `timeline--picked` | The column picked with the keys. |
    """

    DEFAULT_CSS = """
    TimelineStrip { height: 4; background: $surface; }
    TimelineStrip.-hidden { display: none; }
    TimelineStrip > .timeline--debug { color: $foreground-muted; }
    TimelineStrip > .timeline--info { color: $text-success; }
    TimelineStrip > .timeline--warn { color: $text-warning; }
    TimelineStrip > .timeline--error { color: $error; }
    TimelineStrip > .timeline--fatal { color: $accent; }
    TimelineStrip > .timeline--label { color: $foreground-muted; }
    TimelineStrip > .timeline--axis { color: $foreground-muted; }
    TimelineStrip > .timeline--position { color: $text-primary; text-style: bold; }
    TimelineStrip > .timeline--picked { text-style: reverse; }
    TimelineStrip:focus > .timeline--label { color: $foreground; }
    """
    COMPONENT_CLASSES = {
        *(f"timeline--{name}" for name in _SEVERITIES),
        "timeline--label",
        "timeline--axis",
        "timeline--position",
        "timeline--picked",
    }
    BINDINGS = [
        Binding("left", "pick(-1)", "Earlier column", show=False, id="timeline.earlier"),
        Binding("right", "pick(1)", "Later column", show=False, id="timeline.later"),
        Binding("shift+left,pageup", "pick(-10)", "Ten columns earlier", show=False, id="timeline.earlier_10"),
        Binding("shift+right,pagedown", "pick(10)", "Ten columns later", show=False, id="timeline.later_10"),
        Binding("home", "pick_edge(0)", "First column", show=False, id="timeline.first"),
        Binding("end", "pick_edge(1)", "Last column", show=False, id="timeline.last"),
        Binding("enter", "jump", "Show this time in the table", id="timeline.jump"),
        Binding("escape", "leave", "Back to the table", id="timeline.leave"),
    ]

    class Jump(Message):
        """Show the row of ``seq`` (the first shown record of a column) in the table."""

        def __init__(self, seq: int) -> None:
            super().__init__()
            self.seq = seq

    class Leave(Message):
        """Escape: the table takes the focus back."""

    def __init__(self, timeline: Timeline, *, utc: bool = False, id: str | None = None) -> None:
        super().__init__(id=id)
        self.timeline = timeline
        self.utc = utc
        #: Stamps of the first and last rows the table shows, or None.
        self.position: tuple[int, int] | None = None
        #: The time picked with the keys (or the mouse), or None; its column is picked.
        self.picked_ns: int | None = None
        #: Rules hide rows (they are not counted): said on the label line.
        self.filtered = False
        self._lines: list[Strip] = []
        self._key: tuple | None = None
        self._columns: TimelineColumns | None = None

    @property
    def shown(self) -> bool:
        return not self.has_class("-hidden")

    # -- what the app tells it ----------------------------------------------------------------------

    def update_from_model(self, position: tuple[int, int] | None, filtered: bool) -> None:
        """Redraw when the counts, the table's place or the rules changed."""
        if not self.shown:
            return
        self.position = position
        self.filtered = filtered
        if self._lines_key() != self._key:
            self.refresh()

    def _lines_key(self) -> tuple:
        return (
            self.size.width,
            self.timeline.generation,
            self.timeline.recounting,
            self.position,
            self.picked_ns,
            self.filtered,
            self.has_focus,
            self.app.theme if self.is_attached else None,
        )

    # -- drawing ------------------------------------------------------------------------------------

    def render_line(self, y: int) -> Strip:
        key = self._lines_key()
        if key != self._key or not self._lines:
            self._key = key
            self._lines = self._draw(self.size.width)
        return self._lines[y] if y < len(self._lines) else Strip.blank(self.size.width)

    def _style(self, name: str) -> Style:
        return self.get_component_rich_style(f"timeline--{name}", partial=True)

    def _draw(self, width: int) -> list[Strip]:
        base = self.rich_style
        columns = self._columns = self.timeline.columns(width) if width > 0 else None
        if columns is None:
            note = "Timeline: no rows shown" if self.filtered else "Timeline: no messages yet"
            label = Strip([Segment(note, base + self._style("label"))]).adjust_cell_length(width, base)
            return [label, *(Strip.blank(width, base) for _ in range(LINES - 1))]
        return [
            self._label_line(columns, width, base),
            *self._bar_lines(columns, width, base),
            self._mark_line(columns, width, base),
        ]

    def _label_line(self, columns: TimelineColumns, width: int, base: Style) -> Strip:
        style = base + self._style("label")
        first, last = span_text(columns.start_ns, columns.newest_ns, utc=self.utc)
        picked = self.picked_column(columns)
        if picked is not None:
            counts = columns.counts[picked]
            start = columns.start_ns + picked * columns.step_ns
            when = clock_text(start, utc=self.utc, digits=3 if columns.step_ns < 60 * _NS_PER_S else 0)
            marks = " ".join(f"{letter}{counts[slot]:,}" for slot, letter in reversed(_MARKS) if counts[slot])
            middle = (
                f"▸ {when} +{duration_text(columns.step_ns)}: {sum(counts):,} row{'' if sum(counts) == 1 else 's'}"
                + (f" {marks}" if marks else "")
            )
        else:
            middle = f"{duration_text(columns.step_ns)} a column, peak {rate_text(columns.peak_rate())}"
            if self.filtered:
                middle += ", shown rows only"
            if self.timeline.recounting:
                middle += ", counting…"
        left = f"{first}  {middle}"
        room = width - len(last) - 1
        if room < len(first):
            text = left[:width]
        else:
            text = left[:room].ljust(room) + " " + last
        return Strip([Segment(text, style)]).adjust_cell_length(width, base)

    def _bar_lines(self, columns: TimelineColumns, width: int, base: Style) -> list[Strip]:
        severities = [base + self._style(name) for name in _SEVERITIES]
        picked_style = self._style("picked")
        styles: dict[tuple[int | None, int | None, bool], Style] = {}

        def style_of(slot: int | None, behind: int | None, picked: bool) -> Style:
            style = styles.get((slot, behind, picked))
            if style is None:
                style = severities[slot] if slot is not None else base
                if behind is not None and severities[behind].color is not None:
                    style = style + Style(bgcolor=severities[behind].color)
                if picked:
                    style = style + picked_style
                styles[(slot, behind, picked)] = style
            return style

        peak = max(columns.totals(), default=0)
        picked = self.picked_column(columns)
        rows: list[list[tuple[str, Style]]] = [[] for _ in range(_BAR_ROWS)]
        for column, counts in enumerate(columns.counts):
            for row, (glyph, slot, behind) in enumerate(bar_cells(stack(counts, peak))):
                rows[_BAR_ROWS - 1 - row].append((glyph, style_of(slot, behind, column == picked)))
        return [Strip(_runs(cells)).adjust_cell_length(width, base) for cells in rows]

    def _mark_line(self, columns: TimelineColumns, width: int, base: Style) -> Strip:
        axis, position = base + self._style("axis"), base + self._style("position")
        marks = [base + self._style(name) + Style(bold=True) for name in _SEVERITIES]
        picked_style = self._style("picked")
        picked = self.picked_column(columns)
        here = None
        if self.position is not None:
            here = (columns.column_of(self.position[0]), columns.column_of(self.position[1]))
        segments: list[tuple[str, Style]] = []
        for column, counts in enumerate(columns.counts):
            inside = here is not None and here[0] <= column <= here[1]
            glyph, style = ("━", position) if inside else ("─", axis)
            for slot, letter in _MARKS:
                if counts[slot]:
                    glyph, style = letter, marks[slot] + (Style(reverse=True) if inside else Style())
                    break
            if column == picked:
                style = style + picked_style
            segments.append((glyph, style))
        return Strip(_runs(segments)).adjust_cell_length(width, base)

    # -- picking a column ---------------------------------------------------------------------------

    def picked_column(self, columns: TimelineColumns) -> int | None:
        """The column of the picked time (it stays on its time as the columns regroup)."""
        return None if self.picked_ns is None else columns.column_of(self.picked_ns)

    def _pick(self, columns: TimelineColumns, column: int) -> None:
        column = min(max(column, 0), len(columns) - 1)
        self.picked_ns = columns.start_ns + column * columns.step_ns
        self.refresh()

    def _target(self, columns: TimelineColumns, column: int) -> int | None:
        """The seq to show for a column: its first row, else the next column's with rows."""
        later = [seq for seq in columns.first_seqs[column:] if seq is not None]
        if later:
            return later[0]
        earlier = [seq for seq in columns.first_seqs[:column] if seq is not None]
        return earlier[-1] if earlier else None

    def on_click(self, event: events.Click) -> None:
        columns = self._columns
        if columns is None or not 0 <= event.x < len(columns):
            return
        self._pick(columns, event.x)
        target = self._target(columns, event.x)
        if target is not None:
            self.post_message(self.Jump(target))

    def on_focus(self) -> None:
        columns = self._columns or self.timeline.columns(self.size.width)
        if self.picked_ns is None and columns is not None:
            self._pick(columns, self._current_column(columns))

    def on_blur(self) -> None:
        self.picked_ns = None
        self.refresh()

    def _current_column(self, columns: TimelineColumns) -> int:
        """The column of the table's first row on screen (the newest when it is not known)."""
        if self.position is not None:
            return columns.column_of(self.position[0])
        return len(columns) - 1

    def action_pick(self, delta: int) -> None:
        columns = self._columns
        if columns is None:
            return
        picked = self.picked_column(columns)
        self._pick(columns, (picked if picked is not None else self._current_column(columns)) + delta)

    def action_pick_edge(self, end: int) -> None:
        columns = self._columns
        if columns is not None:
            self._pick(columns, len(columns) - 1 if end else 0)

    def action_jump(self) -> None:
        columns = self._columns
        picked = self.picked_column(columns) if columns is not None else None
        if columns is None or picked is None:
            return
        target = self._target(columns, picked)
        if target is not None:
            self.post_message(self.Jump(target))

    def action_leave(self) -> None:
        self.post_message(self.Leave())
