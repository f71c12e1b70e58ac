"""Screen benchmark: event-loop stalls and key-to-effect while messages pour in.

    .venv/bin/python benchmarks/screen.py [--rates 10000 20000] [--seconds 20] [--feed process]

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
  frame drawn with the cursor moved.
Prints a table with the targets beside the figures: longest stall at most the floor +
10 ms, worst key at most 100 ms.
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

from console_tui.model.intake_queue import IntakeQueue
from console_tui.sources.intake_process.parent import ProcessSource
from console_tui.sources.intake_process.synthetic import PERIOD_S, synthetic_record
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp

STALL_OVER_FLOOR_MS = 10.0
KEY_TARGET_MS = 100.0
WARM_UP_S = 2.0
#: Records in the store before each run, so that keys have rows to move over.
PREFILL = 100_000


class ThreadFeed:
    """``rate`` records a second put into ``queue`` from a thread of this process."""

    def __init__(self, queue: IntakeQueue, rate: float) -> None:
        self.queue, self.rate = queue, rate
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
            self.queue.put([synthetic_record(number) for number in range(made, due)])
            made = due


async def run(rate: float, seconds: float, feed: str, size: tuple[int, int]) -> dict[str, float]:
    queue = IntakeQueue()
    source: Any = (
        ProcessSource(queue, "synthetic", args=["--rate", str(rate)]) if feed == "process" else ThreadFeed(queue, rate)
    )
    app = ConsoleApp(queue=queue, sources=[source] if rate else [])
    app.store.extend([synthetic_record(number) for number in range(PREFILL)])
    gc.collect()
    async with app.run_test(size=size):
        frames = count_frames(app.table)
        stalls = StallProbe()
        keys = KeyProbe(app, app.table, frames)
        stalls.start()
        await asyncio.sleep(WARM_UP_S)  # the intake process starts, the tail is followed
        stalls.stalls.clear()
        app.collection_policy.longest = 0.0
        stored_before = app.store.end_seq
        pid = getattr(source, "pid", None)
        cpu_before = (time.process_time(), process_cpu(pid) if pid else 0.0)
        began = time.perf_counter()
        keys.start()
        while time.perf_counter() - began < seconds:
            await asyncio.sleep(0.1)
            del frames[:-100]
        keys.stop()
        elapsed = time.perf_counter() - began
        cpu_app = (time.process_time() - cpu_before[0]) / elapsed * 100
        cpu_intake = ((process_cpu(pid) if pid else 0.0) - cpu_before[1]) / elapsed * 100
        measured = await stalls.stop()
        result = {
            "rate": (app.store.end_seq - stored_before) / elapsed,
            "stored": len(app.store),
            "stall_max": max(measured, default=0.0) * 1000,
            "stall_p99": percentile(measured, 0.99) * 1000,
            "key_median": percentile(keys.latencies, 0.5) * 1000,
            "key_max": max(keys.latencies, default=0.0) * 1000,
            "keys": len(keys.latencies),
            "gc_longest": app.collection_policy.longest * 1000,
            "cpu_app": cpu_app,
            "cpu_intake": cpu_intake,
            "rss_app": process_rss_mb(os.getpid()),
            "rss_intake": process_rss_mb(pid) if pid else 0.0,
        }
    return result


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rates", type=int, nargs="+", default=[10_000, 20_000])
    parser.add_argument("--seconds", type=float, default=20.0, help="measured seconds per rate (default 20)")
    parser.add_argument("--feed", choices=["process", "thread"], default="process")
    parser.add_argument("--size", default="160x48", help="terminal size, COLUMNSxROWS")
    args = parser.parse_args()
    width, height = (int(n) for n in args.size.split("x"))
    print(machine_line(), file=sys.stderr, flush=True)
    floor = asyncio.run(run(0, args.seconds, args.feed, (width, height)))
    results = {rate: asyncio.run(run(rate, args.seconds, args.feed, (width, height))) for rate in args.rates}

    print("## Screen benchmark (benchmarks/screen.py)\n")
    print(machine_line())
    print(f"{args.size} headless, feed: {args.feed}, {args.seconds:g} s per rate after {WARM_UP_S:g} s of warm-up\n")
    rows = [["records stored a second", "0", *(f"{results[rate]['rate']:,.0f}" for rate in args.rates), ""]]
    figures = [
        ("longest event-loop stall ms", "stall_max", f"floor + {STALL_OVER_FLOOR_MS:.0f}"),
        ("event-loop stall, 99th percentile ms", "stall_p99", ""),
        ("key to effect, median ms", "key_median", ""),
        ("key to effect, worst ms", "key_max", f"{KEY_TARGET_MS:.0f}"),
        ("keys pressed", "keys", ""),
        ("longest full garbage collection ms", "gc_longest", ""),
        ("CPU % of a core, app (feeding thread included)", "cpu_app", ""),
        ("CPU % of a core, intake process", "cpu_intake", ""),
        ("RSS MB, app", "rss_app", ""),
        ("RSS MB, intake process", "rss_intake", ""),
    ]
    for title, key, target in figures:
        rows.append([title, f"{floor[key]:.1f}", *(f"{results[rate][key]:.1f}" for rate in args.rates), target])
    print(table(["figure", "nothing arriving", *(f"{rate:,}/s" for rate in args.rates), "target"], rows))
    print("\nTargets:")
    for rate in args.rates:
        result = results[rate]
        limit = floor["stall_max"] + STALL_OVER_FLOOR_MS
        print(
            f"- {rate:,}/s: longest stall <= floor + {STALL_OVER_FLOOR_MS:.0f} ms ({limit:.0f}): "
            f"{result['stall_max']:.0f} ms, " + verdict(result["stall_max"] <= limit, "missed")
        )
        print(
            f"- {rate:,}/s: worst key to effect <= {KEY_TARGET_MS:.0f} ms: {result['key_max']:.0f} ms, "
            + verdict(result["key_max"] <= KEY_TARGET_MS, "missed")
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
