"""Search benchmark: the next match near the far end of a full store, and the event loop meanwhile.

    .venv/bin/python benchmarks/search.py [--records 1000000] [--repeat 3] [--kind '/need(le|ful) \\d+/']

Runs the real app headless (Textual's test driver, 160x48) over ``--records`` synthetic
records (the screen benchmark's, ``synthetic_record``) with nothing arriving. Two messages
hold the searched text: one near the top, one near the far end (5,000 records before the
newest). With the cursor on the first row, a person types the search (``f``, the text, key by
key): the first match is near the top; then ``n`` at once, while the search is still walking
the history, asks for the next, near the far end. Measured for a plain text, a text ignoring
case and a regex:
- first match: from the last key typed to the first frame with the cursor on the near match;
- next match: from ``n`` to the first frame with the cursor on the far match (the search
  walks a million messages to get there), and the CPU time the process spent meanwhile (the
  search's walk and the app's frames; on a shared machine wall-clock times are other
  processes' turns too);
- every match counted: from the last key typed to "match 2 of 2" being known;
- the walk alone, without the app: CPU time to look at every record, and the longest slice
  (the app gives the walk slices of ``SEARCH_BUDGET_S``, 5 ms, between frames);
- longest event-loop stall while the search runs (the screen benchmark's probe: a task that
  sleeps 1 ms at a time), from the first key typed in the search line to every match
  counted (the keys typed, Enter closing the line, ``n``, the walk), beside the floor: the
  same app's longest stall while Down and Up are pressed every 1/8 s with nothing searched
  (drawing a frame is part of both); both also as the CPU time the event loop's thread spent
  in that stall. Opening the search line (``f``: the screen laid out again, before any search) is
  reported apart, as its own column.
Targets: next match within 300 ms, no stall over the floor + 10 ms.
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from _probe import StallProbe, count_frames
from _report import machine_line, table, verdict

from console_tui.model.store.log_store import LogStore
from console_tui.sources.intake_process.synthetic import synthetic_record
from console_tui.ui.app import ConsoleApp
from console_tui.ui.controllers.search import SEARCH_BUDGET_S

NEXT_TARGET_MS = 300.0
STALL_OVER_FLOOR_MS = 10.0
FLOOR_S = 3.0
#: The matches: the 11th record, and 5,000 records before the newest.
NEAR = 10
FAR_BEFORE_END = 5_000
#: What is searched, and the text the two messages get. "needle" ignores case (no capital).
KINDS = [
    ("plain text, case kept", "Needle", "Needle in the haystack"),
    ("plain text, ignoring case", "needle", "NEEDLE in the haystack"),
    ("regex", r"/need(le|ful) \d+/", "needle 42 in the haystack"),
]


async def wait_for(condition, frames: list[float], since: float, timeout: float = 30.0) -> float:
    """Seconds from ``since`` to the first frame drawn after ``condition()`` holds."""
    while not condition():
        if time.perf_counter() - since > timeout:
            return timeout
        await asyncio.sleep(0.0005)
    held = time.perf_counter()
    while True:
        drawn = [frame for frame in frames if frame >= held]
        if drawn:
            return drawn[0] - since
        if time.perf_counter() - held > timeout:
            return timeout
        await asyncio.sleep(0.0005)


async def press(app: ConsoleApp, key: str, character: str | None = None) -> float:
    from textual import events

    pressed = time.perf_counter()
    app.post_message(events.Key(key, character))
    return pressed


async def run(count: int, text: str, message: str) -> dict[str, float]:
    records = [synthetic_record(number) for number in range(count)]
    near, far = NEAR, count - FAR_BEFORE_END
    records[near].msg = message
    records[far].msg = message.replace("42", "43")
    store = LogStore(max_messages=count)
    store.extend_records(records)
    del records
    gc.collect()
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(160, 48)) as pilot:
        frames = count_frames(app.main.table)
        await pilot.press("home")
        await pilot.pause()
        stalls = StallProbe()
        stalls.start()
        # The floor: the same app drawing what keys ask for (Down, Up), nothing searched.
        began = time.perf_counter()
        while time.perf_counter() - began < FLOOR_S:
            for key in ("down", "up"):
                await press(app, key)
                await asyncio.sleep(0.125)
        floor, floor_cpu = max(stalls.stalls, default=0.0), max(stalls.loop_cpu, default=0.0)
        stalls.clear()

        await press(app, "f")
        await asyncio.sleep(0.2)
        # The search line is open: what it cost is reported apart (no search runs yet).
        opening = max(stalls.stalls, default=0.0)
        stalls.clear()
        for character in text[:-1]:
            await press(app, key_of(character), character)
            await asyncio.sleep(0.05)
        typed = await press(app, key_of(text[-1]), text[-1])
        first = await wait_for(lambda: app.main.table.cursor_seq == near, frames, typed)
        await press(app, "enter")
        while app.focused is not app.main.table:  # the search line closes: keys go to the table again
            await asyncio.sleep(0.001)
        cpu = time.process_time()
        pressed = await press(app, "n")
        following = await wait_for(lambda: app.main.table.cursor_seq == far, frames, pressed)
        cpu = time.process_time() - cpu

        def counted() -> bool:
            search = app.main.searching.search
            return search is not None and search.complete

        while not counted() and time.perf_counter() - typed < 60:
            await asyncio.sleep(0.001)
        every = time.perf_counter() - typed
        status = app.main.searching.search_status()
        await asyncio.sleep(0.2)
        measured = await stalls.stop()
    return {
        "first": first * 1000,
        "next": following * 1000,
        "next_cpu": cpu * 1000,
        "every": every * 1000,
        "stall": max(measured, default=0.0) * 1000,
        "floor": floor * 1000,
        "opening": opening * 1000,
        "stall_cpu": max(stalls.loop_cpu, default=0.0) * 1000,
        "floor_cpu": floor_cpu * 1000,
        "ok": float("match 2 of 2" in status),
    }


def walk_alone(count: int, text: str, message: str) -> dict[str, float]:
    """The model's ``Search`` over the same records, from the first to the last, without the app."""
    from console_tui.model.view.log_view import LogView
    from console_tui.model.view.search_walk import Search, parse_search

    records = [synthetic_record(number) for number in range(count)]
    records[NEAR].msg = message
    records[count - FAR_BEFORE_END].msg = message.replace("42", "43")
    store = LogStore(max_messages=count)
    store.extend_records(records)
    del records
    gc.collect()
    search = Search(LogView(store), parse_search(text), 0)
    longest, began = 0.0, time.process_time()
    while not search.complete:
        start = time.perf_counter()
        search.step(SEARCH_BUDGET_S, prefer=1)
        longest = max(longest, time.perf_counter() - start)
    return {"walk_cpu": (time.process_time() - began) * 1000, "walk_slice": longest * 1000}


def key_of(character: str) -> str:
    from textual.keys import _character_to_key

    return _character_to_key(character)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=1, help="runs of each kind; the median is printed")
    parser.add_argument(
        "--kind",
        choices=[text for _title, text, _message in KINDS],
        action="append",
        help="only this search (repeatable)",
    )
    args = parser.parse_args()
    kinds = [kind for kind in KINDS if args.kind is None or kind[1] in args.kind]
    print(machine_line(), file=sys.stderr, flush=True)
    results: dict[str, dict[str, float]] = {}
    for title, text, message in kinds:
        runs = [
            asyncio.run(run(args.records, text, message)) | walk_alone(args.records, text, message)
            for _ in range(args.repeat)
        ]
        results[title] = {key: statistics.median(run[key] for run in runs) for key in runs[0]}
        results[title]["ok"] = min(run["ok"] for run in runs)
        print(f"{title}: {results[title]}", file=sys.stderr, flush=True)

    print("## Search benchmark (benchmarks/search.py)\n")
    print(machine_line())
    print(
        f"160x48 headless, {args.records:,} records, cursor on the first; matches at record {NEAR + 1} and "
        f"{FAR_BEFORE_END:,} before the newest; median of {args.repeat}\n"
    )
    rows = []
    for title, text, _message in kinds:
        result = results[title]
        rows.append(
            [
                f"{title} `{text}`".replace("|", "\\|"),  # a regex's | would end the cell
                f"{result['first']:.0f}",
                f"{result['next']:.0f}",
                f"{result['next_cpu']:.0f}",
                f"{result['every']:.0f}",
                f"{result['walk_cpu']:.0f}",
                f"{result['walk_slice']:.1f}",
                f"{result['stall']:.1f}",
                f"{result['floor']:.1f}",
                f"{result['opening']:.1f}",
                f"{result['stall_cpu']:.1f}",
                f"{result['floor_cpu']:.1f}",
            ]
        )
    headers = [
        "search",
        "first match ms",
        "n to the far match ms",
        "n to the far match, CPU ms",
        "every match counted ms",
        "walk alone, CPU ms",
        "walk alone, longest slice ms",
        "longest stall ms",
        "floor ms (Down / Up drawn)",
        "opening the line (f), longest stall ms",
        "longest stall, CPU ms",
        "floor, CPU ms",
    ]
    print(table(headers, rows))
    print("\nTargets:")
    for title, _text, _message in kinds:
        result = results[title]
        limit = result["floor"] + STALL_OVER_FLOOR_MS
        print(
            f"- {title}: n to the far match <= {NEXT_TARGET_MS:.0f} ms: {result['next']:.0f} ms, "
            + verdict(result["next"] <= NEXT_TARGET_MS, "missed")
            + f"; longest stall <= floor + {STALL_OVER_FLOOR_MS:.0f} ms ({limit:.0f}): {result['stall']:.0f} ms, "
            + verdict(result["stall"] <= limit, "missed")
            + ("" if result["ok"] else "; the status line did not say 'match 2 of 2'")
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
