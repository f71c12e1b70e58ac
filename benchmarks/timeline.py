"""Timeline and storms benchmark: what the overview costs, and how the strip's drawing
compares with the terminal charting libraries that could draw it.

    .venv/bin/python benchmarks/timeline.py [--records 1000000] [--width 160]

- the model: ``Timeline`` and ``StormRows`` taking in records as they arrive (every record
  shown, half of them one storm's repeats), microseconds a record;
- a frame of the strip: ``TimelineStrip`` drawing its four lines over the whole history
  (``Timeline.columns`` included), milliseconds, median and worst of 50;
- Textual's ``Sparkline`` renderable over the same column totals (one series, coloured by
  value: it cannot stack severities or mark them), and plotext's stacked bar chart of the
  same counts, as ``textual-plotext`` draws it (when plotext is installed:
  ``pip install 'plotext<6'``, the versions textual-plotext takes), 3 lines high.

The strip is redrawn at most 4 times a second while messages arrive (the app's
``STRIP_PERIOD_S``); a drawing that takes tens of milliseconds would be a stall of the
live tail (the screen benchmark's target: the floor + 10 ms).
"""

from __future__ import annotations

import argparse
import asyncio
import io
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from _report import machine_line, table
from rich.console import Console
from textual.app import App, ComposeResult
from textual.renderables.sparkline import Sparkline

from console_tui.model.overview.storms import StormRows
from console_tui.model.overview.timeline import Timeline
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView
from console_tui.sources.intake_process.synthetic import START_NS, synthetic_record
from console_tui.ui.widgets.timeline_strip import TimelineStrip

BATCH = 667  # what arrives in one tick of the app at 10,000 records a second


def records(count: int) -> list[LogRecord]:
    made = []
    for number in range(count):
        if number % 2:
            made.append(synthetic_record(number))
        else:
            made.append(LogRecord(START_NS + number * 50_000, 30, "tf_listener", "Lookup would require extrapolation"))
    return made


def model_costs(count: int) -> tuple[dict[str, float], Timeline]:
    """Microseconds a record for the timeline and the storms following a live tail."""
    store = LogStore(max_messages=count)
    view = LogView(store)
    timeline = Timeline(store, view)
    storms = StormRows(store, view)
    feed = records(count)
    spent = {"timeline": 0.0, "storms": 0.0}
    for start in range(0, count, BATCH):
        store.extend_records(feed[start : start + BATCH])
        view.update()
        began = time.perf_counter()
        timeline.sync()
        middle = time.perf_counter()
        storms.sync()
        spent["timeline"] += middle - began
        spent["storms"] += time.perf_counter() - middle
    # After a rule change: everything again, from the oldest record.
    for follower in (timeline, storms):
        follower.restart()
        began = time.perf_counter()
        follower.sync()
        spent[f"{type(follower).__name__} again"] = time.perf_counter() - began
    return {
        "timeline us/record": spent["timeline"] / count * 1e6,
        "storms us/record": spent["storms"] / count * 1e6,
        "timeline, all again s": spent["Timeline again"],
        "storms, all again s": spent["StormRows again"],
        "rows": len(storms),
    }, timeline


def times(action, repeat: int = 50) -> tuple[float, float]:
    taken = []
    for _ in range(repeat):
        began = time.perf_counter()
        action()
        taken.append((time.perf_counter() - began) * 1000)
    return statistics.median(taken), max(taken)


class StripApp(App[None]):
    def __init__(self, timeline: Timeline) -> None:
        super().__init__()
        self.strip = TimelineStrip(timeline, id="timeline")

    def compose(self) -> ComposeResult:
        yield self.strip


async def strip_frame(timeline: Timeline, width: int) -> tuple[float, float]:
    app = StripApp(timeline)
    async with app.run_test(size=(width, 10)) as pilot:
        await pilot.pause()

        def draw() -> None:
            timeline.generation += 1  # as if records arrived: nothing cached
            app.strip._draw(width)

        return times(draw)


def sparkline_frame(timeline: Timeline, width: int) -> tuple[float, float]:
    columns = timeline.columns(width)
    totals = columns.totals() if columns else [0]
    console = Console(width=width, file=io.StringIO(), force_terminal=True)
    return times(lambda: list(console.render(Sparkline(totals, width=width, height=2))))


def plotext_frame(timeline: Timeline, width: int) -> tuple[float, float] | None:
    try:
        import plotext as plt
    except ImportError:
        return None
    columns = timeline.columns(width)
    assert columns is not None
    series = [[counts[slot] for counts in columns.counts] for slot in range(5)]
    xs = list(range(len(columns)))

    def build() -> None:
        plt.clf()
        plt.plotsize(width, 3)
        plt.frame(False)
        plt.xaxes(False, False)
        plt.yaxes(False, False)
        plt.xticks([])
        plt.yticks([])
        plt.stacked_bar(xs, series, color=["gray", "green", "yellow", "red", "magenta"], width=1, minimum=0)
        plt.build()

    return times(build, repeat=20)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=1_000_000)
    parser.add_argument("--width", type=int, default=160)
    args = parser.parse_args()
    costs, timeline = model_costs(args.records)
    strip = asyncio.run(strip_frame(timeline, args.width))
    spark = sparkline_frame(timeline, args.width)
    plot = plotext_frame(timeline, args.width)

    print("## Timeline and storms (benchmarks/timeline.py)\n")
    print(machine_line())
    print(f"{args.records:,} records (half one storm's repeats), taken in {BATCH} at a time; {args.width} columns\n")
    print(
        table(
            ["the model", "figure"],
            [
                ["timeline, µs a record as records arrive", f"{costs['timeline us/record']:.2f}"],
                ["storms, µs a record as records arrive", f"{costs['storms us/record']:.2f}"],
                ["timeline, every record again after a rule change, s", f"{costs['timeline, all again s']:.2f}"],
                ["storms, every record again after a rule change, s", f"{costs['storms, all again s']:.2f}"],
                ["table rows with storms collapsed", f"{costs['rows']:,}"],
            ],
        )
    )
    print()
    rows = [
        ["TimelineStrip (4 lines, stacked severities, marks)", f"{strip[0]:.2f}", f"{strip[1]:.2f}"],
        ["Textual Sparkline (2 lines, totals only)", f"{spark[0]:.2f}", f"{spark[1]:.2f}"],
        (
            ["plotext stacked bar (3 lines), as textual-plotext draws it", f"{plot[0]:.2f}", f"{plot[1]:.2f}"]
            if plot
            else ["plotext stacked bar: not installed (pip install 'plotext<6')", "", ""]
        ),
    ]
    print(table(["a frame of the strip", "median ms", "worst ms"], rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
