"""Screen benchmark: event-loop stalls and key-to-effect while messages pour in.

    .venv/bin/python benchmarks/screen.py [--rates 10000 20000] [--seconds 20] [--feed process]
    .venv/bin/python benchmarks/screen.py --overview both --feed thread --repeats 0.5 --rates 10000

Runs the real app headless (Textual's test driver, real compositor and rendering, 160x48)
with records arriving as console-tui gets them: ``--feed process`` (the default) starts
the intake process with its synthetic source, so records cross the pipe in packed batches
exactly as live ROS 2 messages do; ``--feed thread`` puts ``LogRecord`` batches into the
queue from a thread of the app's own process every 1/50 s, as the intake thread did before
it moved to a process. First the same app with nothing arriving (the floor this machine
sets: drawing, the OS, the hypervisor), then each rate. Measures:
- event-loop stall: a probe task sleeps 1 ms at a time; the worst lateness is the longest
  the loop was busy (a draw, a drain of the queue, a key, a garbage collection);
- key to effect: the time from posting a key (Up, then End to follow again) to the first
  frame drawn with the cursor moved;
- CPU: the app's process, and the event loop's thread alone (what the app does on it, less
  noisy than the stalls on a busy machine: the overview's cost shows there first).
Prints a table with the targets beside the figures: longest stall at most the floor +
10 ms, worst key at most 100 ms.

``--overview both`` runs each rate twice, with the timeline and storms collapsed (as the
app starts) and without them (nothing counted, the strip hidden): the overview's target is
the same key to effect and longest stall within 10 ms. ``--repeats 0.5`` (thread feed)
makes half the records one node's repeats of one message, a storm that never ends.
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import os
import sys
import threading
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from _probe import KeyProbe, StallProbe, count_frames, percentile, process_cpu, process_rss_mb
from _report import machine_line, table, verdict

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.sources.intake_process.parent import ProcessSource
from console_tui.sources.intake_process.synthetic import PERIOD_S, START_NS, synthetic_record
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp

STALL_OVER_FLOOR_MS = 10.0
KEY_TARGET_MS = 100.0
WARM_UP_S = 2.0
#: Records in the store before each run, so that keys have rows to move over.
PREFILL = 100_000


def storm_record(number: int) -> LogRecord:
    return LogRecord(
        START_NS + number * 50_000, 30, "tf_listener", "Lookup would require extrapolation into the future"
    )


class ThreadFeed:
    """``rate`` records a second put into ``queue`` from a thread of this process; a
    fraction ``repeats`` of them one node's repeats of one message."""

    def __init__(self, queue: IntakeQueue, rate: float, repeats: float = 0.0) -> None:
        self.queue, self.rate = queue, rate
        self.every = round(1 / repeats) if repeats else 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self.pid = None
        self.status = SourceStatus(topic="synthetic", path="thread", running=True)

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        self._thread.join()

    def _run(self) -> None:
        made, began = 0, time.monotonic()
        while not self._stop.wait(PERIOD_S):
            due = int((time.monotonic() - began) * self.rate)
            every = self.every
            self.queue.put(
                RecordColumns.from_records(
                    [
                        storm_record(number) if every and number % every == 0 else synthetic_record(number)
                        for number in range(made, due)
                    ]
                )
            )
            made = due


async def run(
    rate: float, seconds: float, feed: str, size: tuple[int, int], *, overview: bool = True, repeats: float = 0.0
) -> dict[str, float]:
    queue = IntakeQueue()
    source: Any = (
        ProcessSource(queue, "synthetic", args=["--rate", str(rate)])
        if feed == "process"
        else ThreadFeed(queue, rate, repeats)
    )
    app = ConsoleApp(queue=queue, sources=[source] if rate else [])
    app.main.store.extend_records([synthetic_record(number) for number in range(PREFILL)])
    gc.collect()
    async with app.run_test(size=size):
        if not overview:
            app.main.overview.set_enabled(False)
        frames = count_frames(app.main.table)
        stalls = StallProbe()
        keys = KeyProbe(app, app.main.table, frames)
        stalls.start()
        await asyncio.sleep(WARM_UP_S)  # the intake process starts, the tail is followed
        stalls.clear()
        app.collection_policy.longest = 0.0
        stored_before = app.main.store.end_seq
        pid = getattr(source, "pid", None)
        cpu_before = (time.process_time(), process_cpu(pid) if pid else 0.0)
        loop_before = time.thread_time()  # this thread runs the event loop
        began = time.perf_counter()
        keys.start()
        while time.perf_counter() - began < seconds:
            await asyncio.sleep(0.1)
            del frames[:-100]
        keys.stop()
        elapsed = time.perf_counter() - began
        cpu_loop = (time.thread_time() - loop_before) / elapsed * 100
        cpu_app = (time.process_time() - cpu_before[0]) / elapsed * 100
        cpu_intake = ((process_cpu(pid) if pid else 0.0) - cpu_before[1]) / elapsed * 100
        measured = await stalls.stop()
        result = {
            "rate": (app.main.store.end_seq - stored_before) / elapsed,
            "stored": len(app.main.store),
            "stall_max": max(measured, default=0.0) * 1000,
            "stall_p99": percentile(measured, 0.99) * 1000,
            "key_median": percentile(keys.latencies, 0.5) * 1000,
            "key_max": max(keys.latencies, default=0.0) * 1000,
            "keys": len(keys.latencies),
            "gc_longest": app.collection_policy.longest * 1000,
            "cpu_app": cpu_app,
            "cpu_loop": cpu_loop,
            "cpu_intake": cpu_intake,
            "rss_app": process_rss_mb(os.getpid()),
            "rss_intake": process_rss_mb(pid) if pid else 0.0,
            "storms": app.main.storms.storm_count if overview else 0,
            "rows": app.main.table.row_count,
        }
    return result


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rates", type=int, nargs="+", default=[10_000, 20_000])
    parser.add_argument("--seconds", type=float, default=20.0, help="measured seconds per rate (default 20)")
    parser.add_argument("--feed", choices=["process", "thread"], default="process")
    parser.add_argument("--size", default="160x48", help="terminal size, COLUMNSxROWS")
    parser.add_argument(
        "--overview",
        choices=["on", "off", "both"],
        default="on",
        help="the timeline and storms (both: with and without)",
    )
    parser.add_argument("--repeats", type=float, default=0.0, help="thread feed: this fraction of records one storm")
    args = parser.parse_args()
    if args.repeats and args.feed != "thread":
        parser.error("--repeats needs --feed thread")
    width, height = (int(n) for n in args.size.split("x"))
    print(machine_line(), file=sys.stderr, flush=True)
    kinds = {"on": [True], "off": [False], "both": [True, False]}[args.overview]
    floor = asyncio.run(run(0, args.seconds, args.feed, (width, height), overview=kinds[0]))
    runs = [(rate, overview) for rate in args.rates for overview in kinds]
    results = {
        key: asyncio.run(run(key[0], args.seconds, args.feed, (width, height), overview=key[1], repeats=args.repeats))
        for key in runs
    }

    def title(key: tuple[int, bool]) -> str:
        rate, overview = key
        return f"{rate:,}/s" + ("" if args.overview != "both" else (" overview on" if overview else " overview off"))

    print("## Screen benchmark (benchmarks/screen.py)\n")
    print(machine_line())
    repeats = f", {args.repeats:.0%} of records one storm" if args.repeats else ""
    print(
        f"{args.size} headless, feed: {args.feed}{repeats}, {args.seconds:g} s per run after {WARM_UP_S:g} s of warm-up\n"
    )
    rows = [["records stored a second", "0", *(f"{results[key]['rate']:,.0f}" for key in runs), ""]]
    figures = [
        ("longest event-loop stall ms", "stall_max", f"floor + {STALL_OVER_FLOOR_MS:.0f}"),
        ("event-loop stall, 99th percentile ms", "stall_p99", ""),
        ("key to effect, median ms", "key_median", ""),
        ("key to effect, worst ms", "key_max", f"{KEY_TARGET_MS:.0f}"),
        ("keys pressed", "keys", ""),
        ("longest full garbage collection ms", "gc_longest", ""),
        ("CPU % of a core, app (feeding thread included)", "cpu_app", ""),
        ("CPU % of a core, the event loop's thread", "cpu_loop", ""),
        ("CPU % of a core, intake process", "cpu_intake", ""),
        ("RSS MB, app", "rss_app", ""),
        ("RSS MB, intake process", "rss_intake", ""),
        ("table rows (storms collapsed)", "rows", ""),
        ("storms", "storms", ""),
    ]
    for name, key, target in figures:
        shape = "{:,.0f}" if key in ("rows", "storms") else "{:.1f}"
        rows.append(
            [name, shape.format(floor[key]), *(shape.format(results[run_key][key]) for run_key in runs), target]
        )
    print(table(["figure", "nothing arriving", *(title(key) for key in runs), "target"], rows))
    print(
        "\nRSS is the whole process's, and the runs are one after another in it: it reads the most of any run so far."
    )
    print("\nTargets:")
    for key in runs:
        result = results[key]
        limit = floor["stall_max"] + STALL_OVER_FLOOR_MS
        print(
            f"- {title(key)}: longest stall <= floor + {STALL_OVER_FLOOR_MS:.0f} ms ({limit:.0f}): "
            f"{result['stall_max']:.0f} ms, "
            + verdict(result["stall_max"] <= limit, f"{result['stall_max'] - limit:.0f} ms over")
        )
        print(
            f"- {title(key)}: worst key to effect <= {KEY_TARGET_MS:.0f} ms: {result['key_max']:.0f} ms, "
            + verdict(result["key_max"] <= KEY_TARGET_MS, f"{result['key_max'] - KEY_TARGET_MS:.0f} ms over")
        )
    if args.overview == "both":
        for rate in args.rates:
            on, off = results[(rate, True)], results[(rate, False)]
            for name, key in (
                ("longest stall", "stall_max"),
                ("worst key to effect", "key_max"),
                ("median key to effect", "key_median"),
            ):
                difference = on[key] - off[key]
                print(
                    f"- {rate:,}/s: {name} with the overview within 10 ms of without: "
                    f"{on[key]:.0f} vs {off[key]:.0f} ms, "
                    + verdict(difference <= 10, f"{difference - 10:.0f} ms over")
                )
            print(
                f"- {rate:,}/s: the event loop's CPU with the overview and without: {on['cpu_loop']:.1f} vs "
                f"{off['cpu_loop']:.1f} % of a core ({(on['cpu_loop'] - off['cpu_loop']) * 10:+.0f} ms a second)"
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
