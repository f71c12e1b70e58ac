"""Opening a whole ROS log directory: time, files open at once, memory.

    .venv/bin/python benchmarks/folders.py [--runs 200] [--records 2000] [--dir DIR]

Writes a log directory of ``--runs`` ROS 1 run folders, one after the other in time (each:
``rosout.log`` with ``--records`` records, ``master.log``, ``roslaunch-*.log``, two rospy
node logs and their ``-stdout.log``), then loads it as the app does (``FileLoad`` in its
thread, merged by time, into a sink that drops the batches) in a fresh process per case,
and prints: files, records, seconds, records/s, the most files open at once, and the
process's peak RSS. The cases: as the loader does it (each file opened when the merge
reaches its time) and, for contrast, every file opened at the start.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _report import machine_line, table

START = 1_700_000_000  # seconds: the first run's start
RUN_SECONDS = 600


def write_log_dir(directory: Path, runs: int, records: int) -> int:
    """The log directory; returns how many files it holds."""
    files = 0
    for run in range(runs):
        folder = directory / f"{run:08x}-d4b2-11eb-9c3e-0242ac110002"
        folder.mkdir(parents=True)
        t0 = START + run * RUN_SECONDS
        step = RUN_SECONDS / max(records, 1)
        with open(folder / "rosout.log", "w") as out:
            out.write(f"\n\n{t0}.000000000  Node Startup\n")
            for k in range(records):
                t = t0 + k * step
                out.write(f"{t:.9f} INFO /talker [talker.py:14(main)] [topics: /rosout] message {k} of run {run}\n")
        for name in ("master", f"roslaunch-robot-{run}"):
            with open(folder / f"{name}.log", "w") as out:
                for k in range(20):
                    clock = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(t0 + k))
                    out.write(f"[{name.split('-')[0]}][INFO] {clock},000: step {k}\n")
        for node in ("talker-2", "listener-3"):
            with open(folder / f"{node}.log", "w") as out, open(folder / f"{node}-stdout.log", "w") as stdout:
                for k in range(records // 10):
                    t = t0 + k * step * 10
                    clock = time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(t))
                    out.write(f"[rosout][INFO] {clock},{int(t * 1000) % 1000:03d}: message {k}\n")
                    stdout.write(f"[INFO] [{t:.6f}]: message {k}\n")
        files += 7
    return files


def measure(directory: Path, eager: bool) -> dict[str, float]:
    """One load, in this process; what it cost."""
    from console_tui.sources.files import FileLoad, loader

    if eager:
        loader.MANY_FILES = 1 << 30  # every file opened at once, as before
    count = 0

    def sink(batch: list) -> None:
        nonlocal count
        count += len(batch)

    most_open = 0
    done = threading.Event()

    def watch() -> None:
        nonlocal most_open
        prefix = str(directory)
        while not done.is_set():
            opened = 0
            for fd in os.listdir("/proc/self/fd"):
                try:
                    opened += os.readlink(f"/proc/self/fd/{fd}").startswith(prefix)
                except OSError:
                    pass
            most_open = max(most_open, opened)
            time.sleep(0.01)

    watcher = threading.Thread(target=watch, daemon=True)
    watcher.start()
    load = FileLoad([directory], sink)
    start = time.perf_counter()
    load.start()
    load.join()
    seconds = time.perf_counter() - start
    done.set()
    watcher.join()
    with open("/proc/self/status") as status:
        peak = next(int(line.split()[1]) for line in status if line.startswith("VmHWM:")) / 1024
    return {
        "files": len(load.progress.files),
        "records": count,
        "seconds": seconds,
        "open": most_open,
        "rss": peak,
        "problems": len(load.problems()),
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=200)
    parser.add_argument("--records", type=int, default=2000, help="rosout.log records per run")
    parser.add_argument("--dir", type=Path, help="where to write the log directory (default: a temporary one)")
    parser.add_argument("--measure", type=Path, help=argparse.SUPPRESS)
    parser.add_argument("--eager", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.measure:
        print(json.dumps(measure(args.measure, args.eager)))
        return 0
    with tempfile.TemporaryDirectory(dir=args.dir) as scratch:
        directory = Path(scratch) / "log"
        files = write_log_dir(directory, args.runs, args.records)
        rows = []
        for label, eager in (("each file when its time comes", False), ("every file at the start", True)):
            command = [sys.executable, __file__, "--measure", str(directory)] + (["--eager"] if eager else [])
            result = json.loads(subprocess.run(command, capture_output=True, text=True, check=True).stdout)
            rows.append(
                [
                    label,
                    f"{result['files']:,}",
                    f"{result['records']:,}",
                    f"{result['seconds']:.1f}",
                    f"{result['records'] / result['seconds']:,.0f}",
                    f"{result['open']:,}",
                    f"{result['rss']:.0f}",
                    f"{result['problems']:,}",
                ]
            )
    print(machine_line())
    print(f"A log directory of {args.runs} ROS 1 runs, {files:,} files, {args.records:,} rosout.log records a run.\n")
    headers = ["opened", "files", "records", "s", "records/s", "most open at once", "peak RSS MB", "problems"]
    print(table(headers, rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
