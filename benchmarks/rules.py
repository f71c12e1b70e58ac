"""Rules benchmark: re-filtering a full store of 1,000,000 records when the rules change.

    .venv/bin/python benchmarks/rules.py [--records 1000000] [--step-ms 15] [--app [--middle]]

Fills a ``LogStore`` with realistic records (60 nodes, 90 files, 120 functions, a ROS-like
mix of severities, 60-120 character messages with numbers), then for each rule change
measures, the way the app drives the view (``set_rules``, then ``refilter_step`` slices from a
background task):
- first screen: from the change until the newest 50 rows are final (they are checked against
  the finished result);
- complete: from the change until every record is filtered;
- longest step: the longest single blocking call (``set_rules`` or one ``refilter_step``),
  which is the longest the event loop would stall;
- CPU to complete: the process's CPU time over the same span (steadier than the wall clock
  on a shared machine).
With ``--app`` the same changes are then made in the running app, headless, and measured
there: the first frame drawn, the end of the background work (the filtering, and the storms
and the timeline counted again), the longest event-loop stall (a probe task). With
``--middle`` the app's selected row is in the middle of the history (not following the
tail): its screenful is the first screen.
Prints a table with the targets beside the figures. Not a test: figures depend on the machine.
"""

from __future__ import annotations

import argparse
import random
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from _report import machine_line

from console_tui.model.rules import (
    CustomRule,
    LocationRule,
    MessageRule,
    NodeRule,
    RuleSet,
    SeverityRule,
    TimeRangeRule,
    exclude,
    highlight,
)
from console_tui.model.rules.query import parse_query
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView

FIRST_SCREEN_TARGET_MS = 100
COMPLETE_TARGET_MS = 1000
STALL_TARGET_MS = 50
SCREEN_ROWS = 50

AREAS = ["nav", "perception", "control", "localization", "drivers", "rviz2", "system", "planning"]
PARTS = ["planner", "controller", "costmap", "lidar", "camera", "imu", "ekf", "amcl", "monitor", "bridge"]
TEMPLATES = [
    "Planner failed to find a path from ({x:.2f}, {y:.2f}) to goal {n}, retrying with tolerance {t:.2f} m",
    "Costmap updated in {ms:.1f} ms: {n} obstacles, resolution 0.05 m/cell, origin ({x:.2f}, {y:.2f})",
    "Received scan {n} with {k} points in {ms:.2f} ms from frame base_laser_link",
    "Timed out waiting for transform from map to base_link after {t:.2f} s (tf buffer {k} entries)",
    "Request timeout on service /{part}/get_state after {ms:.0f} ms, attempt {k} of 5",
    "Battery voltage {t:.2f} V, current {x:.2f} A, estimated {n} minutes remaining",
    "Goal {n} reached: position error {x:.3f} m, heading error {y:.3f} rad, took {t:.1f} s",
    "Dropped {k} packets from 192.0.2.{k} on /{part}/points: checksum mismatch in frame {n}",
    "Controller loop overrun: {ms:.2f} ms over a 10.00 ms period (iteration {n})",
    "Parameter update: max_velocity={t:.2f}, min_velocity={x:.2f}, acc_limit={y:.2f} for {part}",
]
LEVELS = [10] * 20 + [20] * 60 + [30] * 12 + [40] * 7 + [50]
START_NS = 1_795_000_000_000_000_000
#: The newest stamp of a million records (one a millisecond).
LAST_STAMP = START_NS + 999_999 * 1_000_000


def make_records(count: int) -> list[LogRecord]:
    rng = random.Random(7)
    nodes = [f"{rng.choice(AREAS)}.{rng.choice(PARTS)}_{i}" for i in range(60)]
    files = [f"/opt/robot/src/{rng.choice(AREAS)}/src/{rng.choice(PARTS)}_{i}.cpp" for i in range(90)]
    functions = [f"{rng.choice(['on_', 'update_', 'handle_', ''])}{rng.choice(PARTS)}_{i}" for i in range(120)]
    start = START_NS
    records = []
    for i in range(count):
        part = rng.choice(PARTS)
        msg = rng.choice(TEMPLATES).format(
            x=rng.uniform(-50, 50),
            y=rng.uniform(-50, 50),
            t=rng.uniform(0, 30),
            ms=rng.uniform(0, 200),
            n=rng.randrange(100000),
            k=rng.randrange(1, 250),
            part=part,
        )
        records.append(
            LogRecord(
                stamp_ns=start + i * 1_000_000,
                level=rng.choice(LEVELS),
                node=rng.choice(nodes),
                msg=msg,
                file=rng.choice(files),
                function=rng.choice(functions),
                line=rng.randrange(1, 2000),
            )
        )
    return records


def scenarios() -> list[tuple[str, RuleSet]]:
    warn_up = RuleSet((exclude(SeverityRule.of("debug", "info")),))
    example = 'level>=warn node:nav* -node:rviz* "planner failed" /time(out|d out)/i file:planner'
    return [
        ("severity: hide debug, info", warn_up),
        ("node glob: hide rviz2.*", RuleSet((exclude(NodeRule(("rviz2.*",))),))),
        ("text: only 'Planner failed'", RuleSet((exclude(MessageRule("Planner failed"), inverted=True),))),
        ("text, ignore case: hide 'timeout'", RuleSet((exclude(MessageRule("timeout", ignore_case=True)),))),
        ("regex /time(out|d out)/i, highlight", RuleSet((highlight(MessageRule("time(out|d out)", True, True)),))),
        ("  + highlighted only (masks kept)", RuleSet((highlight(MessageRule("time(out|d out)", True, True)),), True)),
        ("regex /\\d{3}\\.\\d ms/, exclude", RuleSet((exclude(MessageRule(r"\d{3}\.\d ms", regex=True)),))),
        (
            "custom: warn+ AND nav* AND 'goal'",
            RuleSet((exclude(CustomRule((SeverityRule.at_least(30), NodeRule(("nav*",)), MessageRule("goal")))),)),
        ),
        ("location: file 'planner', hide", RuleSet((exclude(LocationRule(file="planner")),))),
        (
            "time range: the last 10 minutes only",
            RuleSet((exclude(TimeRangeRule(LAST_STAMP - 600 * 10**9, None), inverted=True),)),
        ),
        ("query: issue example", RuleSet().with_query(parse_query(example))),
        ("everything off again", RuleSet()),
        (
            "4 rules at once",
            RuleSet(
                (
                    exclude(SeverityRule.of("debug")),
                    exclude(NodeRule(("rviz2.*", "system.*"))),
                    highlight(MessageRule("failed", ignore_case=True)),
                    highlight(MessageRule(r"\d{3}\.\d ms", regex=True)),
                )
            ),
        ),
    ]


def measure(view: LogView, rules: RuleSet, step_s: float) -> tuple[float, float, float, int, float]:
    began, cpu_began = time.perf_counter(), time.process_time()
    view.set_rules(rules)
    longest = time.perf_counter() - began
    first_screen = None
    if len(view) >= SCREEN_ROWS or not view.refiltering:
        first_screen = time.perf_counter() - began
    newest = [view.seq_at(r) for r in range(max(len(view) - SCREEN_ROWS, 0), len(view))]
    while view.refiltering:
        t0 = time.perf_counter()
        view.refilter_step(step_s)
        longest = max(longest, time.perf_counter() - t0)
        if first_screen is None and len(view) >= SCREEN_ROWS:
            first_screen = time.perf_counter() - began
            newest = [view.seq_at(r) for r in range(len(view) - SCREEN_ROWS, len(view))]
    complete = time.perf_counter() - began
    cpu = time.process_time() - cpu_began
    final = [view.seq_at(r) for r in range(max(len(view) - SCREEN_ROWS, 0), len(view))]
    assert newest == final, "the first screen was not the final one"
    return (first_screen if first_screen is not None else complete), complete, longest, len(view), cpu


def _screen_rows(app) -> list[int]:
    """The seqs of the rows around the table's cursor (the newest rows while it follows)."""
    view = app.main.table.view
    if app.main.table.following:
        return [view.seq_at(r) for r in range(max(len(view) - SCREEN_ROWS, 0), len(view))]
    row = app.main.table.cursor_row
    return [view.seq_at(r) for r in range(max(row - SCREEN_ROWS // 2, 0), min(row + SCREEN_ROWS // 2, len(view)))]


async def measure_in_app(store: LogStore, middle: bool = False) -> list[tuple[str, float, float, float, int, float]]:
    """The same rule changes made in the running app (headless, 160x48): from the change to
    the first frame showing the final newest rows, to the end of the background filtering,
    and the longest the event loop was busy meanwhile (a probe task sleeping 1 ms)."""
    import asyncio

    from _probe import StallProbe, count_frames

    from console_tui.ui.app import ConsoleApp

    app = ConsoleApp(store=store)
    results = []
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause(0.5)
        while app.main.storms.behind or app.main.timeline.behind:
            await asyncio.sleep(0.05)  # the storms and the timeline counted at start
        if middle:
            app.main.table.jump_to_seq(store.first_seq + len(store) // 2)
        frames = count_frames(app.main.table)
        for name, rules in scenarios():
            probe = StallProbe()
            probe.start()
            await asyncio.sleep(0.05)
            began, cpu_began = time.perf_counter(), time.process_time()
            app.main.filtering.apply_rules(rules)  # as the query line, the pane or a quick rule does
            shown_first = _screen_rows(app)
            while not frames or frames[-1] < began:
                await asyncio.sleep(0.001)
            first_frame = frames[-1] - began
            while app.main.view.refiltering or app.main.storms.behind or app.main.timeline.behind:
                await asyncio.sleep(0.005)
            complete = time.perf_counter() - began
            cpu = time.process_time() - cpu_began
            stalls = await probe.stop()
            final = _screen_rows(app)
            # Nothing arrives meanwhile, so a first screen that was already final stays so.
            first = first_frame if shown_first == final else complete
            results.append((name, first * 1000, complete * 1000, max(stalls) * 1000, len(app.main.view), cpu * 1000))
    return results


def print_table(title: str, rows: list[tuple[str, float, float, float, int, float]], stall_title: str) -> None:
    print(f"\n{title}\n")
    print(
        f"| rule change | first screen ms (<{FIRST_SCREEN_TARGET_MS}) | complete ms (<{COMPLETE_TARGET_MS}) | {stall_title} ms (<{STALL_TARGET_MS}) | rows shown | CPU ms to complete |"
    )
    print("|---|---:|---:|---:|---:|---:|")
    for name, first, complete, longest, shown, cpu in rows:

        def mark(value: float, target: float) -> str:
            return f"{value:.0f}" + ("" if value < target else " ✗")

        print(
            f"| {name} | {mark(first, FIRST_SCREEN_TARGET_MS)} | {mark(complete, COMPLETE_TARGET_MS)} | "
            f"{mark(longest, STALL_TARGET_MS)} | {shown:,} | {cpu:.0f} |"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=1_000_000)
    parser.add_argument("--step-ms", type=float, default=15.0)
    parser.add_argument("--app", action="store_true", help="also make the changes in the running app (headless)")
    parser.add_argument("--middle", action="store_true", help="in the app: the selected row mid-history")
    args = parser.parse_args()

    t0 = time.perf_counter()
    store = LogStore(max_messages=args.records)
    records = make_records(args.records)
    made = time.perf_counter() - t0
    store.extend_records(records)
    del records
    print(
        f"{machine_line()}\n{args.records:,} records made in {made:.1f} s, stored in {time.perf_counter() - t0 - made:.1f} s; "
        f"steps of {args.step_ms:g} ms\n"
    )
    view = LogView(store)
    rows = []
    for name, rules in scenarios():
        first, complete, longest, shown, cpu = measure(view, rules, args.step_ms / 1000)
        rows.append((name, first * 1000, complete * 1000, longest * 1000, shown, cpu * 1000))
    print_table("The model (set_rules, then refilter_step from a loop):", rows, "longest step")
    if args.app:
        import asyncio

        view.set_rules(RuleSet())
        rows = asyncio.run(measure_in_app(store, args.middle))
        print_table(
            "In the running app (headless 160x48; the first screen is the first frame drawn):", rows, "longest stall"
        )


if __name__ == "__main__":
    main()
