"""Screen benchmark: event-loop stalls and key-to-effect while messages pour in.

    .venv/bin/python benchmarks/screen.py [--rate 10000] [--seconds 10] [--presses 40]

Runs the real app headless (Textual's test driver, real compositor and rendering) with a
feeder thread putting ``--rate`` records a second into its intake queue, in batches of
1/50 s, as the ROS intake thread does. Measures:
- event-loop stall: a probe task sleeps 1 ms at a time; the worst lateness is the longest
  the loop was busy (a draw, a drain of the queue, a key);
- key to effect: the time from posting a key (Up, alternating with Down) to the first
  frame drawn with the cursor moved.
Prints a table with the targets beside the figures.
"""

from __future__ import annotations

import argparse
import asyncio
import statistics
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from _probe import StallProbe, count_frames
from _report import machine_line
from feed import record
from textual import events

from console_tui.model.intake_queue import IntakeQueue
from console_tui.ui.app import ConsoleApp

STALL_TARGET_MS = 33
KEY_TARGET_MS = 100


def feeder(queue: IntakeQueue, rate: int, stop: threading.Event, sent: list[int]) -> None:
    period = 0.02
    per_batch = max(1, int(rate * period))
    i = 0
    next_time = time.perf_counter()
    while not stop.is_set():
        queue.put([record(i + k) for k in range(per_batch)])
        i += per_batch
        next_time += period
        delay = next_time - time.perf_counter()
        if delay > 0:
            time.sleep(delay)
    sent.append(i)


async def run(rate: int, seconds: float, presses: int, size: tuple[int, int] = (160, 48)) -> dict[str, float]:
    queue = IntakeQueue()
    app = ConsoleApp(queue=queue)
    stop = threading.Event()
    sent: list[int] = []
    key_latencies: list[float] = []
    async with app.run_test(size=size) as pilot:
        table = app.table
        frames = count_frames(table)
        thread = threading.Thread(target=feeder, args=(queue, rate, stop, sent), daemon=True)
        thread.start()
        probe = StallProbe()
        probe.start()
        await asyncio.sleep(1.0)  # warm up: the store fills, the tail is followed
        probe.stalls.clear()
        started = time.perf_counter()
        interval = max((seconds - 1.0) / max(presses, 1), 0.05)
        for n in range(presses):
            key = "up" if n % 2 == 0 else "down"
            cursor_before = table.cursor_row if key == "up" else None
            pressed = time.perf_counter()
            app.post_message(events.Key(key, None))
            while True:
                await asyncio.sleep(0.001)
                moved = table.cursor_row != cursor_before if cursor_before is not None else not table.following
                drawn = [f for f in frames if f > pressed]
                if moved and drawn:
                    key_latencies.append(drawn[0] - pressed)
                    break
                if time.perf_counter() - pressed > 2.0:
                    key_latencies.append(2.0)
                    break
            await pilot.press("end") if key == "down" else None
            await asyncio.sleep(interval)
        elapsed = time.perf_counter() - started
        stalls = await probe.stop()
        stop.set()
        thread.join()
        shown = len(app.store)
    return {
        "rate": sent[0] / (elapsed + 1.0) if sent else 0.0,
        "stored": shown,
        "stall_max": max(stalls) * 1000,
        "stall_p99": statistics.quantiles(stalls, n=100)[98] * 1000,
        "key_median": statistics.median(key_latencies) * 1000,
        "key_max": max(key_latencies) * 1000,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rate", type=int, default=10_000)
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--presses", type=int, default=40)
    args = parser.parse_args()
    parser.add_argument("--size", default="160x48", help="terminal size, COLUMNSxROWS")
    args = parser.parse_args()
    size = tuple(int(n) for n in args.size.split("x"))
    # The same app, keys and probe with (almost) nothing arriving: the floor this machine
    # sets for stalls (drawing after a key, the OS, the hypervisor).
    floor = asyncio.run(run(1, args.seconds, args.presses, size))
    result = asyncio.run(run(args.rate, args.seconds, args.presses, size))

    def verdict(value: float, target: float) -> str:
        return "met" if value <= target else f"MISSED by {value - target:.1f} ms"

    print(machine_line())
    print(f"feed: {result['rate']:,.0f} records/s offered, {result['stored']:,} stored, {args.size} headless\n")
    print(f"| figure | at {args.rate:,}/s | with nothing arriving | target | |")
    print("| --- | --- | --- | --- | --- |")
    rows = [
        ("longest event-loop stall", "stall_max", STALL_TARGET_MS),
        ("event-loop stall, 99th percentile", "stall_p99", None),
        ("key to effect, median", "key_median", KEY_TARGET_MS),
        ("key to effect, worst", "key_max", KEY_TARGET_MS),
    ]
    for title, key, target in rows:
        judged = f"{target} ms | {verdict(result[key], target)}" if target else " | "
        print(f"| {title} | {result[key]:.1f} ms | {floor[key]:.1f} ms | {judged} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
