#!/usr/bin/env python3
"""Warehouse benchmark: a table of 5,000,000 rows in the exporter's schema, read by the console.

The table ``otel_logs`` (the OpenTelemetry Collector ClickHouse exporter's DDL) is written by
SQL, as a collector would write it: 50 robots, 20 nodes, six hours, mostly INFO and DEBUG, one
row in 50 a WARN and one in 500 an ERROR, and three rare FATAL rows ("reactor core breach").
It is kept in ``--dir`` between runs (chDB: ClickHouse's engine, in this process).

Then, in the running app (headless 160x48, the console as ``console-tui chdb://DIR`` makes it):
the first screen (from making the app until the newest rows are drawn), each rule change until
the new answer's newest rows are drawn (the query line, ``level>=error``, ``robot:robot7``, a
text), the longest stall of the event loop meanwhile, and the RSS once the window holds
1,000,000 rows (paged back a page at a time, as scrolling past the top does), beside the RSS
of the app over a store of 1,000,000 records made in memory (chDB's engine runs in a process of
its own, ``warehouse/chdb_child.py``: its RSS is said beside). Last, ``console-tui tail
chdb://DIR --query '"reactor core breach"'``: its time and the rows it printed.

    python benchmarks/warehouse.py                    # the table made once (about a minute)
    python benchmarks/warehouse.py --rows 1000000 --dir /tmp/wh-1m
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests")]

from _probe import StallProbe, process_rss_mb  # noqa: E402
from _report import machine_line  # noqa: E402

from console_tui.model.store.log_store import LogStore  # noqa: E402
from console_tui.sources.warehouse_source import WarehouseSource  # noqa: E402
from console_tui.ui.app import ConsoleApp  # noqa: E402
from console_tui.warehouse.address import parse_address  # noqa: E402
from console_tui.warehouse.clickhouse import TableClient  # noqa: E402

from support.ui import screen_text, type_text  # noqa: E402

HOURS = 6
RARE = "reactor core breach"


def make_table(directory: Path, rows: int) -> float:
    """The table of ``rows`` rows (made again only when it holds another count); seconds taken."""
    address = parse_address(f"chdb://{directory}")
    client = TableClient(address, create=True)
    try:
        client.create_table()
        if client.value("SELECT count() FROM default.otel_logs") == rows:
            return 0.0
        client._client.command("TRUNCATE TABLE default.otel_logs")
        began = time.perf_counter()
        end_ns = time.time_ns()
        step = HOURS * 3600 * 1_000_000_000 // rows
        chunk = 1_000_000
        for start in range(0, rows, chunk):
            count = min(chunk, rows - start)
            client._client.command(
                f"""INSERT INTO default.otel_logs (Timestamp, SeverityText, SeverityNumber, ServiceName, Body,
                ResourceAttributes, ScopeName, LogAttributes)
                SELECT fromUnixTimestamp64Nano(toInt64({end_ns} - ({rows} - n) * {step})),
                  multiIf(n IN (1234567 % {rows}, 2345678 % {rows}, 3456789 % {rows}), 'FATAL',
                          n % 500 = 7, 'ERROR', n % 50 = 3, 'WARN', n % 5 = 0, 'DEBUG', 'INFO'),
                  multiIf(n IN (1234567 % {rows}, 2345678 % {rows}, 3456789 % {rows}), 21,
                          n % 500 = 7, 17, n % 50 = 3, 13, n % 5 = 0, 5, 9),
                  concat('nav.node', toString(n % 20)),
                  if(n IN (1234567 % {rows}, 2345678 % {rows}, 3456789 % {rows}),
                     concat('{RARE} at sector ', toString(n % 97)),
                     concat('planned path ', toString(n), ': ', toString(n % 311), ' poses, costmap ',
                            toString(n % 977), ' cells, goal (', toString(n % 13), '.5, -2.25)')),
                  map('service.name', concat('nav.node', toString(n % 20)),
                      'service.namespace', concat('robot', toString(intDiv(n, 7) % 50)),
                      'host.name', concat('robot', toString(intDiv(n, 7) % 50))),
                  concat('nav.node', toString(n % 20)),
                  map('code.file.path', concat('/opt/robot/src/nav/module_', toString(n % 6), '.cpp'),
                      'code.function.name', ['plan', 'update', 'on_timer'][1 + n % 3],
                      'code.line.number', toString(n % 2000))
                FROM (SELECT number + {start} AS n FROM numbers({count}))"""
            )
        return time.perf_counter() - began
    finally:
        client.close()


async def until(pilot, condition, timeout: float = 300.0) -> float:
    """Seconds until ``condition`` holds, looked at every 5 ms (an asyncio sleep: the pilot's
    pause waits for the app's queues to empty as well, which is not what a person sees)."""
    began = time.perf_counter()
    while not condition():
        if time.perf_counter() - began > timeout:
            raise TimeoutError("the screen never showed it")
        await asyncio.sleep(0.005)
    return time.perf_counter() - began


def chdb_children_rss_mb() -> float:
    """The resident memory of this process's chDB children (``warehouse/chdb_child.py``)."""
    total = 0.0
    for task in Path(f"/proc/{os.getpid()}/task").iterdir():  # the warehouse's thread started it
        for child in (task / "children").read_text().split():
            try:
                if b"chdb_child" in Path(f"/proc/{child}/cmdline").read_bytes():
                    total += process_rss_mb(int(child))
            except OSError:
                pass
    return total


def newest_row(client: TableClient, where: str = "1") -> str:
    return str(client.value(f"SELECT Body FROM default.otel_logs WHERE {where} ORDER BY Timestamp DESC LIMIT 1"))


async def in_the_app(directory: Path, queries: list[tuple[str, str]]) -> dict:
    address = parse_address(f"chdb://{directory}")
    client = TableClient(address)
    expected = {query: newest_row(client, where) for query, where in queries}
    newest = newest_row(client)
    client.close()
    results: dict = {}
    began = time.perf_counter()
    source = WarehouseSource(address, max_rows=1_000_000)
    app = ConsoleApp(store=LogStore(), sources=[source], utc=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await until(pilot, lambda: newest[:60] in screen_text(app))
        results["first screen"] = time.perf_counter() - began
        probe = StallProbe()
        probe.start()
        for query, _ in queries:
            generation = source.generation
            await pilot.press("slash")
            await pilot.press("ctrl+u")
            await type_text(pilot, query)
            probe.clear()
            changed = time.perf_counter()
            await pilot.press("enter")
            await until(
                pilot, lambda g=generation, q=query: source.generation > g and expected[q][:60] in screen_text(app)
            )
            results[f"rule change: {query}"] = (time.perf_counter() - changed, probe.longest()[0])
        await pilot.press("slash")
        await pilot.press("ctrl+u")
        await pilot.press("enter")  # no query: the whole window again
        await until(pilot, lambda: newest[:60] in screen_text(app))
        probe.clear()
        paged = time.perf_counter()
        longest_page = 0.0
        while len(app.main.store) < 1_000_000 and not source.at_start:
            count = len(app.main.store)
            page_began = time.perf_counter()
            await pilot.press("home", "home")
            await until(pilot, lambda c=count: len(app.main.store) > c or source.at_start)
            longest_page = max(longest_page, time.perf_counter() - page_began)
        results["paged back to"] = (len(app.main.store), time.perf_counter() - paged, longest_page, probe.longest()[0])
        await probe.stop()
        gc.collect()
        results["rss"] = process_rss_mb(os.getpid())
        results["chdb rss"] = chdb_children_rss_mb()
    source.stop()
    return results


def rss_of_a_million_in_memory() -> float:
    """The app's RSS over 1,000,000 records made in memory (another process: a clean start),
    records like the table's rows (``make_table``'s expressions, in Python)."""
    code = f"""
import asyncio, sys
sys.path[:0] = [{str(HERE)!r}, {str(HERE.parent / "tests")!r}]
import os
from _probe import process_rss_mb
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.ui.app import ConsoleApp
LEVELS = {{"FATAL": 50, "ERROR": 40, "WARN": 30, "DEBUG": 10, "INFO": 20}}
def row(n):
    level = "ERROR" if n % 500 == 7 else "WARN" if n % 50 == 3 else "DEBUG" if n % 5 == 0 else "INFO"
    message = (f"planned path {{n}}: {{n % 311}} poses, costmap {{n % 977}} cells, goal ({{n % 13}}.5, -2.25)")
    return LogRecord(1_765_000_000_000_000_000 + n * 4_320_000, LEVELS[level], f"nav.node{{n % 20}}", message,
                     f"/opt/robot/src/nav/module_{{n % 6}}.cpp", ["plan", "update", "on_timer"][n % 3], n % 2000,
                     source="chdb:///table", robot=f"robot{{n // 7 % 50}}")
async def main():
    store = LogStore()
    for start in range(4_000_000, 5_000_000, 50_000):
        store.extend_records([row(i) for i in range(start, start + 50_000)])
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(160, 48)) as pilot:
        await pilot.pause(1)
        import gc; gc.collect()
        print(process_rss_mb(os.getpid()))
asyncio.run(main())
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    return float(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rows", type=int, default=5_000_000, help="rows of the table (default 5,000,000)")
    parser.add_argument("--dir", type=Path, default=Path("/tmp/console-tui-warehouse-5m"), help="the chDB directory")
    args = parser.parse_args()
    made = make_table(args.dir, args.rows)
    queries = [
        ("level>=error", "SeverityNumber >= 17"),
        ("robot:robot7", "ResourceAttributes['service.namespace'] = 'robot7'"),
        ("robot:robot7 level>=warn", "ResourceAttributes['service.namespace'] = 'robot7' AND SeverityNumber >= 13"),
        ('"poses, costmap 97 "', "position(Body, 'poses, costmap 97 ') > 0"),
        ("/goal \\(1[12]\\.5/", "match(Body, 'goal \\\\(1[12]\\\\.5')"),
    ]
    results = asyncio.run(in_the_app(args.dir, queries))
    began = time.perf_counter()
    tail = subprocess.run(
        [sys.executable, "-m", "console_tui", "tail", f"chdb://{args.dir}", "--query", f'"{RARE}"', "--no-color"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    tail_s = time.perf_counter() - began
    memory = rss_of_a_million_in_memory()
    print(machine_line())
    print()
    print(f"Table: {args.rows:,} rows in chDB ({args.dir}){f', written in {made:.0f} s' if made else ''}.")
    print()
    print("| what | seconds | longest stall ms |")
    print("|---|---|---|")
    print(f"| first screen of `console-tui chdb://...` | {results['first screen']:.2f} | |")
    for key, value in results.items():
        if key.startswith("rule change"):
            print(f"| {key.replace('rule change: ', 'rule change: `')}` | {value[0]:.2f} | {value[1] * 1000:.0f} |")
    rows, seconds, longest, stall = results["paged back to"]
    print(f"| paged back to {rows:,} rows (longest page {longest:.2f} s) | {seconds:.1f} | {stall * 1000:.0f} |")
    printed = [line for line in tail.stdout.splitlines() if line.strip()]
    print(f"| `tail --query '\"{RARE}\"'`: {len(printed)} rows printed | {tail_s:.2f} | |")
    print()
    print(
        f"RSS of the app with {rows:,} warehouse rows: {results['rss']:.0f} MB (its chDB process beside it: "
        f"{results['chdb rss']:.0f} MB); of the app over 1,000,000 records made in memory: {memory:.0f} MB"
    )
    for line in printed:
        print("   ", line)


if __name__ == "__main__":
    main()
