#!/usr/bin/env python3
"""``console-tui tail --level error`` beside a node logging 20,000 DEBUG messages a second: the
console's CPU with the DDS content filter, without it (the intake drops them), and without
``--level``.

One publisher process of ``intake.py`` (``--publisher c``: rcl's publish from C, as a node in
C++ logs) sends pre-serialized ``rcl_interfaces/msg/Log`` messages with ``/rosout``'s QoS at
``--rate`` a second for ``--duration`` seconds, every one DEBUG but one in 512, an ERROR (about
39 a second at 20,000/s). Against the same publisher, one after another, each started fresh:

- ``no --level``: ``tail`` printing everything (to a pipe this script counts);
- ``--level error, no filter``: ``CONSOLE_TUI_CONTENT_FILTER=0``: every message taken,
  decoded and dropped in the intake process;
- ``--level error, DDS filter``: the content filter ``level >= 40`` on the subscriptions
  (Fast DDS filters on the writer's side: the DEBUG messages are never sent).

The console's CPU is the ``tail`` process's and its intake process's while the publisher
sends, in % of one core; the publisher's CPU beside it (writer-side filtering is its work).

    python benchmarks/level_filter.py                  # 20,000/s for 10 s, median of 3
    python benchmarks/level_filter.py --rate 50000 --duration 5 --repeat 1
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _probe import process_cpu
from _report import ros_environment, ros_header, run_under_header, table
from intake import TOPIC, Child

#: Each variant: its name, tail's extra arguments and environment.
VARIANTS: tuple[tuple[str, tuple[str, ...], dict[str, str]], ...] = (
    ("no --level", (), {}),
    ("--level error, no filter", ("--level", "error"), {"CONSOLE_TUI_CONTENT_FILTER": "0"}),
    ("--level error, DDS filter", ("--level", "error"), {}),
)


def children(pid: int) -> list[int]:
    """The process's children (its intake process), from /proc."""
    found: list[int] = []
    try:
        for task in os.listdir(f"/proc/{pid}/task"):
            with open(f"/proc/{pid}/task/{task}/children", encoding="ascii") as listing:
                found += [int(child) for child in listing.read().split()]
    except OSError:
        pass
    return found


class Tail:
    """``console-tui tail`` with its lines counted."""

    def __init__(self, args: tuple[str, ...], env: dict[str, str]) -> None:
        command = [sys.executable, "-m", "console_tui", "tail", "--topic", TOPIC, "--format", "{message}", *args]
        self.process = subprocess.Popen(
            command, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=env
        )
        self.lines = 0
        self._reader = threading.Thread(target=self._count, daemon=True)
        self._reader.start()

    def _count(self) -> None:
        assert self.process.stdout is not None
        for _line in self.process.stdout:
            self.lines += 1

    def cpu(self) -> float:
        return sum(process_cpu(pid) for pid in [self.process.pid, *children(self.process.pid)])

    def stop(self) -> None:
        self.process.send_signal(signal.SIGINT)
        try:
            self.process.wait(15)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self._reader.join(5)


def measure_once(publisher: Child, env: dict[str, str], variant: tuple, args: argparse.Namespace) -> dict:
    name, extra, more_env = variant
    tail = Tail(extra, {**env, **more_env})
    try:
        publisher.ask("matched", cmd="matched", count=1)
        time.sleep(2.0)  # discovery settled, the publisher's history delivered
        lines_before, cpu_before = tail.lines, tail.cpu()
        publisher_before = process_cpu(publisher.process.pid)
        publisher.send(cmd="go", rate=args.rate, duration=args.duration)
        done = publisher.expect("done", args.duration + 60)
        time.sleep(0.5)  # what was sent, printed
        cpu = tail.cpu() - cpu_before
        publisher_cpu = process_cpu(publisher.process.pid) - publisher_before
        printed = tail.lines - lines_before
    finally:
        tail.stop()
        publisher.ask("matched", cmd="matched", count=0)
    seconds = done["elapsed"]
    print(f"  {name:<26} {cpu / seconds:6.1%} of a core, {printed:,} lines", file=sys.stderr, flush=True)
    return {"name": name, "sent": done["sent"], "seconds": seconds, "cpu": cpu, "pub": publisher_cpu, "lines": printed}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rate", type=float, default=20_000.0, help="messages a second (default 20000)")
    parser.add_argument("--duration", type=float, default=10.0, help="seconds of sending (default 10)")
    parser.add_argument("--repeat", type=int, default=3, help="rounds; the table shows medians (default 3)")
    parser.add_argument(
        "--domain", type=int, default=150 + os.getpid() % 80, help="ROS_DOMAIN_ID (default: from the pid)"
    )
    args = parser.parse_args()
    env = ros_environment(args.domain)
    header = ros_header(
        "tail --level and the DDS content filter (benchmarks/level_filter.py)",
        env,
        f"one publisher (rcl from C) at {args.rate:,.0f}/s for {args.duration:g} s, "
        f"one message in 512 an ERROR, the rest DEBUG; median of {args.repeat}.",
    )

    def run() -> list[dict]:
        publisher = Child(["--role", "publisher", "--publisher", "c", "--pool", "debug"], env)
        try:
            publisher.expect("ready")
            runs: dict[str, list[dict]] = {variant[0]: [] for variant in VARIANTS}
            for round_number in range(args.repeat):
                shift = round_number % len(VARIANTS)  # the order varies, so drifting load hits all alike
                for variant in VARIANTS[shift:] + VARIANTS[:shift]:
                    runs[variant[0]].append(measure_once(publisher, env, variant, args))
        finally:
            publisher.close()
        return [sorted(found, key=lambda row: row["cpu"])[len(found) // 2] for found in runs.values()]

    rows = run_under_header(header, run)
    print(
        table(
            ["tail", "sent/s", "lines printed", "console CPU (tail + intake)", "publisher CPU"],
            [
                [
                    row["name"],
                    f"{row['sent'] / row['seconds']:,.0f}",
                    f"{row['lines']:,}",
                    f"{row['cpu'] / row['seconds']:.1%}",
                    f"{row['pub'] / row['seconds']:.1%}",
                ]
                for row in rows
            ],
        )
    )


if __name__ == "__main__":
    main()
