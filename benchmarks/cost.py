#!/usr/bin/env python3
"""Cost benchmark: what one log message costs on its way from the pipe to the screen, by stage.

    .venv/bin/python benchmarks/cost.py [--rates 20000 50000] [--records 300000] [--rounds 5]

Each stage runs alone on the same realistic records (``benchmarks/store.py``'s
``RecordMaker``: messages of 60-120 characters, 40 nodes, 120 files), in the batches the intake process sends at each rate (one
every 20 ms), timed with the thread's own CPU clock (``time.thread_time``: what the stage
costs, not how long the machine made it wait); the table shows medians of ``--rounds``.

- ``pack``: the intake process turns a batch of columns into a frame's bytes (``BatchPacker``);
- ``pipe``: writing the frame into a pipe and reading it out (both ends' system calls and
  the frame reader);
- ``unpack``: the app's pipe thread turns the bytes into columns again (``BatchUnpacker``);
- ``store``: ``LogStore.extend``, sealing and packing full chunks included;
- ``view and overview``: the rows shown (``LogView.update``), the storms and the timeline
  following them, as the app does on each tick (15 a second);
- ``nodes' counts``: ``NodeStats`` kept up to date, once a second, as while the node panel is
  open (closed, the app counts nothing);
- ``frame``: drawing the table, the timeline strip and the status line again (160x48), as
  the app does once a tick while records arrive, divided among the tick's records (measured
  in the real app, headless: ``--frames`` seconds of frames, their median).

With ``--full`` the store is full, as in any long session: it keeps a third of the records
(the first third fills it, untimed), so every batch after that makes it drop as many of the
oldest, and each stage pays for what it kept about them.

Taking a message from DDS and decoding it (the intake's take loop in C) needs ROS:
``benchmarks/take_loop.py`` measures it, and ``benchmarks/intake.py`` the whole intake
process (Fast DDS's receive thread included) and the whole app.
"""

from __future__ import annotations

import argparse
import asyncio
import fcntl
import os
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from _report import machine_line, table
from store import RecordMaker

from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record_batch import BatchPacker, BatchUnpacker, RecordColumns
from console_tui.sources.intake_process.frames import BATCH, read_frames, write_frame

#: The intake process sends what it took every this many seconds (``child.FLUSH_S``).
FLUSH_S = 0.02
#: The app moves what came into the store and draws once a tick (``DRAIN_INTERVAL``).
TICK_S = 1 / 15
_F_SETPIPE_SZ = 1031


def realistic_batches(records: int, rate: int) -> list[RecordColumns]:
    """``records`` realistic records in the batches the intake process sends at ``rate``."""
    size = max(1, int(rate * FLUSH_S))
    made = RecordMaker().batch(records)
    return [RecordColumns.from_records(made[at : at + size]) for at in range(0, records, size)]


def timed(work: Callable[[], Any]) -> float:
    """CPU seconds of this thread that ``work`` took."""
    began = time.thread_time()
    work()
    return time.thread_time() - began


def stage_costs(batches: list[RecordColumns], kept: int | None = None) -> dict[str, float]:
    """CPU seconds of each stage over ``batches``; with ``kept``, the store keeps that many
    records and the stages after the store are timed only once it is full."""
    from console_tui.model.overview.node_stats import NodeStats
    from console_tui.model.overview.storms import StormRows
    from console_tui.model.overview.timeline import Timeline
    from console_tui.model.view.log_view import LogView

    packer = BatchPacker()
    payloads: list[bytes] = []
    costs = {"pack": timed(lambda: payloads.extend(packer.pack(batch) for batch in batches))}

    reading, writing = os.pipe()
    try:
        fcntl.fcntl(writing, _F_SETPIPE_SZ, 1 << 20)
        largest = max(len(payload) for payload in payloads)
        if largest + 16 > fcntl.fcntl(writing, 1032):  # F_GETPIPE_SZ: a frame must fit
            raise SystemExit("a frame is larger than the pipe can hold; use a lower rate")
        frames = read_frames(reading)
        received: list[bytes] = []

        def through_pipe() -> None:
            for payload in payloads:
                write_frame(writing, BATCH, payload)
                received.append(next(frames)[1])

        costs["pipe"] = timed(through_pipe)
    finally:
        os.close(writing)
        os.close(reading)

    unpacker = BatchUnpacker()
    columns: list[RecordColumns] = []
    costs["unpack"] = timed(lambda: columns.extend(unpacker.unpack(payload) for payload in received))

    store = LogStore() if kept is None else LogStore(max_messages=kept)
    view = LogView(store)
    storms, timeline, nodes = StormRows(store, view), Timeline(store, view), NodeStats(store)
    store_s = overview_s = nodes_s = 0.0
    # What the counts' eviction hook takes (inside the store's ``extend``) is theirs.
    hooks = store.evict_listeners
    uncounting = [0.0]

    def timed_hook(first: int, new_first: int, hook: Callable[[int, int], None] = hooks[-1]) -> None:
        uncounting[0] += timed(lambda: hook(first, new_first))

    assert hooks[-1] == nodes._evicting  # NodeStats hooks in last
    hooks[-1] = timed_hook
    per_tick = max(1, round(TICK_S / FLUSH_S))
    ticks_a_second = round(1 / TICK_S)
    for number, tick in enumerate(range(0, len(columns), per_tick)):
        warming = kept is not None and store.end_seq < kept
        for batch in columns[tick : tick + per_tick]:
            uncounting[0] = 0.0
            spent = timed(lambda batch=batch: store.extend(batch))
            store_s += 0.0 if warming else spent - uncounting[0]
            nodes_s += 0.0 if warming else uncounting[0]
        began = time.thread_time()
        view.update()
        storms.sync()
        timeline.sync()
        overview_s += 0.0 if warming else time.thread_time() - began
        if number % ticks_a_second == 0:
            spent = timed(nodes.update)
            nodes_s += 0.0 if warming else spent
    costs["store"] = store_s
    costs["view and overview"] = overview_s
    costs["nodes' counts"] = nodes_s
    return costs


def frame_cost(size: tuple[int, int], seconds: float) -> float:
    """CPU seconds a frame of the app takes: the table (last rows changed), its scroll bar,
    the timeline strip and the status line drawn anew, in the real app, headless."""
    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.ui.app import ConsoleApp

    app = ConsoleApp(queue=IntakeQueue(), sources=[])
    records = RecordMaker().batch(200_000)
    app.main.store.extend(RecordColumns.from_records(records[:100_000]))
    costs: list[float] = []

    async def run() -> None:
        async with app.run_test(size=size) as pilot:
            await pilot.pause()
            at, step = 100_000, 200
            deadline = time.monotonic() + seconds
            while time.monotonic() < deadline and at + step <= len(records):
                app.main.queue.put(RecordColumns.from_records(records[at : at + step]))
                at += step
                await pilot.pause()  # the tick drains them
                await pilot.pause()
                began = time.thread_time()
                for widget in (app.main.table, app.main.status_bar, app.main.timeline_strip):
                    widget.refresh()
                await pilot.pause()
                costs.append(time.thread_time() - began)

    asyncio.run(run())
    return statistics.median(costs) if costs else 0.0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rates", type=int, nargs="+", default=[20_000, 50_000])
    parser.add_argument("--records", type=int, default=300_000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--frames", type=float, default=5.0, metavar="S", help="seconds of frames measured (0: none)")
    parser.add_argument("--size", default="160x48")
    parser.add_argument("--full", action="store_true", help="the store full: it keeps a third of the records")
    args = parser.parse_args()
    width, height = (int(n) for n in args.size.split("x"))
    print(machine_line(), file=sys.stderr, flush=True)
    stages = ["pack", "pipe", "unpack", "store", "view and overview", "nodes' counts"]
    kept = args.records // 3 if args.full else None
    timed_records = {stage: args.records for stage in stages}
    if kept is not None:  # only the records after the first third are timed there
        for stage in ("store", "view and overview", "nodes' counts"):
            timed_records[stage] = args.records - kept
    per_rate: dict[int, dict[str, float]] = {}
    for rate in args.rates:
        batches = realistic_batches(args.records, rate)
        rounds = [stage_costs(batches, kept) for _ in range(args.rounds)]
        per_rate[rate] = {
            stage: statistics.median(r[stage] for r in rounds) / timed_records[stage] * 1e6 for stage in stages
        }
    frame_s = frame_cost((width, height), args.frames) if args.frames > 0 else 0.0
    ticks = 1 / TICK_S
    body = []
    for stage in stages:
        body.append([stage, *(f"{per_rate[rate][stage]:.2f}" for rate in args.rates)])
    if frame_s:
        body.append(["frame", *(f"{frame_s * ticks / rate * 1e6:.2f}" for rate in args.rates)])
    totals = [sum(per_rate[rate].values()) + (frame_s * ticks / rate * 1e6 if frame_s else 0.0) for rate in args.rates]
    body.append(["all of these", *(f"{total:.2f}" for total in totals)])
    print("## Cost benchmark (benchmarks/cost.py)\n")
    print(machine_line())
    print(
        f"{args.records:,} realistic records in the batches the intake sends every {FLUSH_S * 1000:.0f} ms; "
        + (f"the store full (it keeps {kept:,}: the first {kept:,} untimed after packing); " if kept else "")
        + f"CPU a message in microseconds, medians of {args.rounds}"
        + (f"; a frame ({args.size}) costs {frame_s * 1000:.1f} ms, {ticks:.0f} a second" if frame_s else "")
        + "\n"
    )
    print(table(["stage", *(f"at {rate:,}/s" for rate in args.rates)], body))
    return 0


if __name__ == "__main__":
    sys.exit(main())
