#!/usr/bin/env python3
"""Big-file benchmark: a ROS 2 node log of 20,000,000 lines opened, scrolled, filtered and searched.

    .venv/bin/python benchmarks/big_file.py                           # 20,000,000 lines in /tmp (made if missing)
    .venv/bin/python benchmarks/big_file.py --records 1000000 5000000 20000000   # the table against size
    .venv/bin/python benchmarks/big_file.py --lnav                    # also lnav on the same files (Debian's)
    .venv/bin/python benchmarks/big_file.py --cli                     # also the real command, from its launch

Runs the real app headless (Textual's test driver, 160x48) as ``console-tui FILE`` runs it
(its history on disk, in a temporary directory) over a file ``make_big_log.py`` makes, and
measures, with the process's RSS sampled every 50 ms throughout:
- first screen: from making the app to the first frame showing a record (Python's own start
  and imports before it are not counted here: ``--cli`` counts them);
- Home and End (``G``) while the file is still being read, and again once it is read: from
  the key to the first frame with the cursor on the first (last) record;
- read: until the load is done ("Loaded 20,000,000 records"), and until the timeline and the
  storms have counted every record;
- a level rule (``level>=warn``, as the query line applies it): its first screen (the first
  frame after the change, if its rows are the final ones) and until every record is decided;
- search to the far match: with the cursor on the newest record, the search for ``NEEDLE``
  (held by the 1,000th message only): from the search to the frame with the cursor on it;
- the longest event-loop stall meanwhile (a task that sleeps 1 ms at a time).
Targets (issue 48): first screen 1 s, Home/End 1 s, the rule's first screen 100 ms and
complete 10 s, the far match 3 s, RSS 300 MB. With ``--lnav``, lnav 0.11 (Debian 12) opens
the same file headless: ``lnav -n -c ':goto 100%'`` (it indexes the whole file first) with
its wall time and peak RSS (``/usr/bin/time``). With ``--cli``, the real ``console-tui FILE`` in a
pseudo-terminal (``startup.py``'s launch): from the launch to the first row on the screen, Python's
start and imports counted, and from ``q`` until it and its files are gone.
"""

from __future__ import annotations

import argparse
import asyncio
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from _probe import StallProbe, count_frames
from _report import machine_line, table
from make_big_log import NEEDLE, make
from startup import launch, write_bytecode

from console_tui.model.store.chunk_spill import ChunkSpill
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.spill_file import SpillFiles
from console_tui.ui.app import ConsoleApp

TARGETS = {"first": 1.0, "home": 1.0, "end": 1.0, "rule first": 0.1, "rule": 10.0, "search": 3.0, "rss": 300.0}
TIMEOUT_S = 600.0


class RssSampler:
    """The process's RSS every ``period`` seconds, on a thread of its own: the largest seen."""

    def __init__(self, period: float = 0.05) -> None:
        self.period = period
        self.peak = 0.0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop.wait(self.period):
            self.peak = max(self.peak, rss_mb())

    def __enter__(self) -> RssSampler:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


def rss_mb() -> float:
    with open("/proc/self/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return 0.0


async def until(condition, timeout: float = TIMEOUT_S) -> None:
    began = time.perf_counter()
    while not condition():
        if time.perf_counter() - began > timeout:
            raise TimeoutError
        await asyncio.sleep(0.001)


async def to_frame(frames: list[float], condition, since: float) -> float:
    """Seconds from ``since`` to the first frame drawn once ``condition()`` holds."""
    await until(condition)
    held = time.perf_counter()
    await until(lambda: frames and frames[-1] >= held)
    return frames[-1] - since


async def key(app: ConsoleApp, name: str, frames: list[float], condition) -> float:
    from textual import events

    pressed = time.perf_counter()
    app.post_message(events.Key(name, None))
    return await to_frame(frames, condition, pressed)


async def run(path: Path, records: int, size: tuple[int, int]) -> dict[str, float]:
    results: dict[str, float] = {}
    directory = Path(tempfile.mkdtemp(prefix="big-file-history-"))
    with RssSampler() as rss:
        began = time.perf_counter()
        store = LogStore(spill=ChunkSpill(SpillFiles(directory)))
        app = ConsoleApp(store=store, files=[str(path)], utc=True)
        async with app.run_test(size=size) as pilot:
            main = app.main
            table, view = main.table, main.view
            frames = count_frames(table)
            stalls = StallProbe()
            stalls.start()
            results["first"] = await to_frame(frames, lambda: len(view) > 0, began)
            await asyncio.sleep(max(0.0, 2.0 - (time.perf_counter() - began)))
            if main.files.loading:  # while the file is still being read
                results["home, reading"] = await key(app, "home", frames, lambda: table.cursor_seq == 0)
                results["end, reading"] = await key(app, "end", frames, lambda: table.following)
            await until(lambda: not main.files.loading and len(store) == records)
            results["read"] = time.perf_counter() - began
            await until(lambda: not (main.storms.behind or main.timeline.behind))
            results["counted"] = time.perf_counter() - began
            results["home"] = await key(app, "home", frames, lambda: table.cursor_seq == 0)
            results["end"] = await key(app, "end", frames, lambda: table.cursor_seq == store.end_seq - 1)
            await pilot.pause(0.2)

            from console_tui.model.rules.query import parse_query
            from console_tui.model.rules.ruleset import RuleSet

            stalls.clear()
            changed = time.perf_counter()
            main.filtering.apply_rules(RuleSet().with_query(parse_query("level>=warn")))
            first_rows = [view.seq_at(row) for row in range(max(len(view) - 40, 0), len(view))]
            results["rule first"] = await to_frame(frames, lambda: True, changed)
            await until(lambda: not view.refiltering)
            results["rule"] = time.perf_counter() - changed
            final = [view.seq_at(row) for row in range(max(len(view) - 40, 0), len(view))]
            if first_rows != final:
                results["rule first"] = results["rule"]
            results["rule stall"] = stalls.longest()[0]
            await until(lambda: not (main.storms.behind or main.timeline.behind))
            main.filtering.apply_rules(RuleSet())
            await until(lambda: not view.refiltering and not (main.storms.behind or main.timeline.behind))

            await pilot.press("end")
            await pilot.pause(0.2)
            stalls.clear()
            searched = time.perf_counter()
            main.searching.start_search(NEEDLE, first_jump=True, newest_first=True)
            results["search"] = await to_frame(frames, lambda: table.cursor_seq == 999, searched)
            results["search stall"] = stalls.longest()[0]
            await stalls.stop()
        results["rss"] = rss.peak
        results["disk MB"] = sum(f.stat().st_size for f in directory.iterdir()) / 1e6 if directory.exists() else 0
    shutil.rmtree(directory, ignore_errors=True)
    return results


def lnav(path: Path) -> tuple[float, float]:
    """lnav's seconds to open the file and go to its end (headless), and its peak RSS (MB)."""
    done = subprocess.run(
        ["/usr/bin/time", "-f", "%e %M", "lnav", "-n", "-c", ":goto 100%", str(path)],
        capture_output=True,
        text=True,
        timeout=TIMEOUT_S,
    )
    seconds, kilobytes = done.stderr.strip().splitlines()[-1].split()
    return float(seconds), int(kilobytes) / 1024


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--records", type=int, nargs="+", default=[20_000_000])
    parser.add_argument("--dir", type=Path, default=Path(tempfile.gettempdir()), help="where the files are (made)")
    parser.add_argument("--size", default="160x48")
    parser.add_argument("--lnav", action="store_true", help="also lnav on the same files")
    parser.add_argument("--keep", action="store_true", help="keep the files made (else removed at the end)")
    parser.add_argument(
        "--cli",
        action="store_true",
        help="also `console-tui FILE` in a pseudo-terminal (160x48): from its launch to the first row on the "
        "screen (Python's start and imports counted), and from q until it is gone",
    )
    args = parser.parse_args()
    width, height = (int(n) for n in args.size.split("x"))
    if args.cli:
        write_bytecode()  # as an installed package has them (else each launch compiles the modules)
    rows = []
    for records in args.records:
        path = args.dir / f"console-tui-big-{records}.log"
        made = not path.exists()
        if made:
            print(f"making {path} ...", file=sys.stderr, flush=True)
            make(path, records)
        subprocess.run(["cat", str(path)], stdout=subprocess.DEVNULL, check=False)  # in the page cache, as lnav has it
        found = asyncio.run(run(path, records, (width, height)))
        line = [
            f"{records:,}",
            f"{path.stat().st_size / 1e9:.2f} GB",
            f"{found['first']:.2f}",
            f"{found.get('home, reading', float('nan')):.2f} / {found.get('end, reading', float('nan')):.2f}",
            f"{found['read']:.1f} / {found['counted']:.1f}",
            f"{found['home']:.2f} / {found['end']:.2f}",
            f"{found['rule first'] * 1000:.0f} ms / {found['rule']:.2f} s",
            f"{found['search']:.2f}",
            f"{max(found['rule stall'], found['search stall']) * 1000:.0f} ms",
            f"{found['rss']:.0f} MB",
            f"{found['disk MB']:.0f} MB",
        ]
        if args.cli:
            command = [str(Path(sys.executable).parent / "console-tui"), str(path)]
            launched = launch(command, domain=93, marker="robot.", timeout=TIMEOUT_S)
            line.append(f"{launched.row:.2f} / {launched.quit:.2f}")
        if args.lnav:
            seconds, peak = lnav(path)
            line.append(f"{seconds:.1f} s, {peak:.0f} MB")
        rows.append(line)
        if made and not args.keep:
            path.unlink()
    headers = [
        "records",
        "file",
        "first screen s",
        "Home / End while reading s",
        "read / counted s",
        "Home / End s",
        "level rule: first screen / complete",
        "far match s",
        "longest stall",
        "peak RSS",
        "history on disk",
    ]
    if args.cli:
        headers.append("console-tui FILE: launch to the first row / q to gone s")
    if args.lnav:
        headers.append("lnav: open to the end, peak RSS")
    print("## Big-file benchmark (benchmarks/big_file.py)\n")
    print(machine_line())
    targets = ", ".join(f"{name} {value:g}" for name, value in TARGETS.items())
    print(f"headless {args.size}; targets: {targets} (seconds, MB)\n")
    print(table(headers, rows))


if __name__ == "__main__":
    main()
