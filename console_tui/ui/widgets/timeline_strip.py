"""The timeline strip above the table: the message rate over the whole history, by severity.

Four lines, drawn with the line API from ``Timeline.columns`` (the model does the counting;
the drawing is ``timeline_drawing.py``, mixed in):

- the time span, the duration of a column and the peak rate (or, on a picked column, its
  time and counts);
- two lines of bars, 16 steps high, the severities stacked in their colours (DEBUG at the
  bottom, FATAL on top; a cell holding several shows the worst of them);
- a line that reads without colour: ``F`` ``E`` ``W`` under columns with a FATAL, an ERROR,
  a WARN message, and the table's place in the history as ``━`` on the axis ``─``.

A click on a column, or Enter on the column picked with the arrows while the strip has the
focus, asks the app to show that time in the table (``Jump``).

Why not Textual's ``Sparkline`` or plotext: docs/decisions/0018-own-widgets.md
(``benchmarks/timeline.py`` measures both against this strip).
"""

from __future__ import annotations

from dataclasses import dataclass

from textual import events
from textual.binding import Binding
from textual.message import Message
from textual.strip import Strip

from ...model.overview.timeline import Timeline, TimelineColumns
from .timeline_drawing import SEVERITIES, TimelineDrawing


class TimelineStrip(TimelineDrawing, can_focus=True):
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
        *(f"timeline--{name}" for name in SEVERITIES),
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

    @dataclass
    class Jump(Message):
        """Show the row of ``seq`` (the first shown record of a column) in the table."""

        seq: int

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
        #: The timeline's counts the strip is to show (as of ``update_from_model``).
        self._counts_key: tuple[int, bool] = (-1, False)

    @property
    def shown(self) -> bool:
        return not self.has_class("-hidden")

    # -- what the app tells it ----------------------------------------------------------------------

    def update_from_model(self, position: tuple[int, int] | None, filtered: bool) -> None:
        """Redraw when the counts, the table's place on the axis or the rules changed."""
        if not self.shown:
            return
        self.position = position
        self.filtered = filtered
        self._counts_key = (self.timeline.generation, self.timeline.recounting)
        if self._lines_key() != self._key:
            self.refresh()

    def _lines_key(self) -> tuple:
        return (
            self.size.width,
            self._counts_key,
            self._position_columns(),
            self.picked_ns,
            self.filtered,
            self.has_focus,
            self.app.theme if self.is_attached else None,
        )

    def _position_columns(self) -> tuple[int, int] | None:
        """The columns the table's place covers on the strip as drawn (its stamps change
        with every row that arrives while the table follows; its columns seldom do)."""
        position, columns = self.position, self._columns
        if position is None or columns is None:
            return position
        return columns.column_of(position[0]), columns.column_of(position[1])

    # -- drawing ------------------------------------------------------------------------------------

    def render_line(self, y: int) -> Strip:
        key = self._lines_key()
        if key != self._key or not self._lines:
            self._lines = self._draw(self.size.width)
            self._key = self._lines_key()  # the table's place in the columns just drawn
        return self._lines[y] if y < len(self._lines) else Strip.blank(self.size.width)

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
