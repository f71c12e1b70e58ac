#!/usr/bin/env python3
"""Rosout benchmark: how many messages a second ``console-tui rosout`` forwards, at what CPU
cost per message, and whether it loses any.

For each offered rate, a fresh ``console-tui rosout`` process (writing rosout.log into a
temporary directory, rotation at 100M) takes ``/rosout`` from publisher processes
(benchmarks/intake.py's: realistic pre-serialized Log messages, ``/rosout``'s QoS), and a
raw counting subscriber (EventsExecutor) takes ``/rosout_agg``. Measured:

- forwarded/s: records written to rosout.log while the publishers sent, per second;
- CPU: the aggregator process's user + system time over the run (from /proc), as a share
  of one core and per forwarded message;
- lost in: sent but never written to rosout.log (of which "reported": what the aggregator
  itself counted as lost, from the middleware's message-lost events and its queue);
  lost out: sent but never received on /rosout_agg by the subscriber.

Once the publishers are done and rosout.log has stopped growing for 2 s, the aggregator is
stopped (SIGINT) and the counts are taken.

Every ROS process uses ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of its own.

    python benchmarks/rosout.py                          # 10k and 20k msg/s, 10 s each
    python benchmarks/rosout.py --rates 10000 20000 max --duration 20 --repeat 3
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _report import ros_environment, ros_header, run_under_header, table
from intake import Child, message_pool, settle

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_RATES = ("10000", "20000")
TICKS = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process so far."""
    with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
        fields = stat.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICKS


def records_in(directory: Path) -> int:
    """Records in rosout.log and its rotated files (lines that start with a stamp)."""
    count = 0
    for path in directory.glob("rosout.log*"):
        with open(path, "rb") as file:
            count += sum(1 for line in file if line[:1].isdigit())
    return count


def settled_records(directory: Path, quiet: float = 1.0, limit: float = 60.0) -> int:
    last = records_in(directory)
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        time.sleep(quiet)
        now = records_in(directory)
        if now == last:
            return now
        last = now
    return last


@dataclass
class Row:
    rate: str
    sent: int
    seconds: float
    in_window: int
    written: int
    received: int
    cpu: float
    lost_reported: int | None

    @property
    def forwarded_per_s(self) -> float:
        return self.in_window / self.seconds

    @property
    def cpu_share(self) -> float:
        return self.cpu / self.seconds

    @property
    def us_per_message(self) -> float:
        return self.cpu / max(self.written, 1) * 1e6


def measure_once(args: argparse.Namespace, env: dict[str, str], rate: str, workdir: Path) -> Row:
    log_dir = workdir / f"rate-{rate}-{time.monotonic_ns()}"
    aggregator = subprocess.Popen(
        [sys.executable, "-m", "console_tui", "rosout", "--log-dir", str(log_dir), "--report-every", "0"],
        cwd=ROOT,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    summary = ""
    publishers = [
        Child(["--role", "publisher", "--index", str(i), "--topic", "/rosout"], env) for i in range(args.publishers)
    ]
    subscriber = Child(["--role", "subscriber", "--kind", "raw-ee", "--topic", "/rosout_agg"], env)
    try:
        for child in (*publishers, subscriber):
            child.expect("ready")
        subscriber.ask("publishers", cmd="publishers", count=1)
        for child in publishers:
            child.ask("matched", cmd="matched", count=1)
        before_written = settled_records(log_dir)
        before_received = settle(subscriber)["count"]
        cpu_before = cpu_seconds(aggregator.pid)
        per_publisher = 0.0 if rate == "max" else float(rate) / len(publishers)
        for child in publishers:
            child.send(cmd="go", rate=per_publisher, duration=args.duration)
        done = [child.expect("done", args.duration + 120) for child in publishers]
        in_window = records_in(log_dir) - before_written
        settled_records(log_dir, quiet=2.0)
        cpu = cpu_seconds(aggregator.pid) - cpu_before
        summary = _stop(aggregator)
        written = records_in(log_dir) - before_written
        received = settle(subscriber)["count"] - before_received
    finally:
        subscriber.close()
        for child in publishers:
            child.close()
        if not summary:
            summary = _stop(aggregator)
    reported = re.search(r"([\d,]+) lost", summary)
    row = Row(
        rate=rate,
        sent=sum(d["sent"] for d in done),
        seconds=max(d["elapsed"] for d in done),
        in_window=in_window,
        written=written,
        received=received,
        cpu=cpu,
        lost_reported=int(reported.group(1).replace(",", "")) if reported else None,
    )
    print(
        f"  {rate:>6}: sent {row.sent:>9,} written {row.written:>9,} received {row.received:>9,} "
        f"({row.forwarded_per_s:,.0f}/s, {row.us_per_message:.1f} us/msg)",
        file=sys.stderr,
        flush=True,
    )
    return row


def _stop(aggregator: subprocess.Popen) -> str:
    """SIGINT, and the aggregator's last words (its summary line)."""
    if aggregator.poll() is None:
        aggregator.send_signal(signal.SIGINT)
    try:
        _, err = aggregator.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        aggregator.kill()
        _, err = aggregator.communicate()
    if os.environ.get("BENCH_DEBUG"):
        print(err, file=sys.stderr)
    return err or ""


def report(rows: list[Row]) -> str:
    return table(
        [
            "offered msg/s",
            "sent",
            "forwarded msg/s",
            "written",
            "lost in (reported)",
            "received on /rosout_agg",
            "lost out",
            "CPU (share of a core)",
            "CPU us/msg",
        ],
        [
            [
                row.rate if row.rate == "max" else f"{int(row.rate):,}",
                f"{row.sent:,}",
                f"{row.forwarded_per_s:,.0f}",
                f"{row.written:,}",
                f"{max(row.sent - row.written, 0):,} ({'?' if row.lost_reported is None else f'{row.lost_reported:,}'})",
                f"{row.received:,}",
                f"{max(row.sent - row.received, 0):,}",
                f"{row.cpu_share * 100:.0f}%",
                f"{row.us_per_message:.1f}",
            ]
            for row in rows
        ],
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--rates", nargs="+", default=list(DEFAULT_RATES), help="offered msg/s, or max (default 10000 20000)"
    )
    parser.add_argument("--duration", type=float, default=10.0, help="seconds of sending per measurement (default 10)")
    parser.add_argument("--publishers", type=int, default=2, help="publisher processes (default 2)")
    parser.add_argument("--repeat", type=int, default=1, help="rounds per rate; the table shows medians")
    parser.add_argument(
        "--domain", type=int, default=150 + os.getpid() % 80, help="ROS_DOMAIN_ID (default: from the pid)"
    )
    args = parser.parse_args()
    env = ros_environment(
        args.domain, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))
    )
    header = ros_header(
        "Rosout benchmark (benchmarks/rosout.py)",
        env,
        f"{args.publishers} publisher processes; {args.duration:g} s per measurement, median of {args.repeat}; "
        f"messages {len(message_pool(0)[0])}-ish bytes serialized; rosout.log on {tempfile.gettempdir()}.",
    )

    def medians() -> list[Row]:
        rows: list[Row] = []
        with tempfile.TemporaryDirectory(prefix="console-tui-rosout-bench-") as workdir:
            for rate in args.rates:
                runs = sorted(
                    (measure_once(args, env, rate, Path(workdir)) for _ in range(args.repeat)),
                    key=lambda row: row.forwarded_per_s,
                )
                rows.append(runs[len(runs) // 2])
        return rows

    print(report(run_under_header(header, medians)))


if __name__ == "__main__":
    main()
