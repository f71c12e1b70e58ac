#!/usr/bin/env python3
"""Ship benchmark: ``console-tui ship`` at a steady rate, the CPU it costs a message, and what it lost.

A real rclpy publisher process (``intake.py``'s) sends pre-serialized ``rcl_interfaces/msg/Log``
messages with ``/rosout``'s QoS at ``--rate`` for ``--duration`` seconds; ``console-tui ship``
reads them as on a robot (its intake process, its spool on disk) and sends them over OTLP/HTTP
(protobuf, gzip) to a receiver in this process that decodes each request with opentelemetry-proto
and counts the records. CPU is the shipper's and its intake process's (user + system, from
/proc), from the first message to the last one sent; lost is what was published and never
arrived. ``--via-rotel`` puts a real collector (rotel) between them.

    python benchmarks/ship.py                         # 20,000 msg/s for 60 s (the issue's row)
    python benchmarks/ship.py --rate 5000 --duration 10
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests")]

from _report import machine_line  # noqa: E402
from intake import TOPIC, Child  # noqa: E402

from support.otlp_receiver import OtlpReceiver  # noqa: E402


def process_tree_cpu(pid: int) -> float:
    """User + system seconds of ``pid`` and its children (the intake process)."""
    total = 0.0
    ticks = os.sysconf("SC_CLK_TCK")
    pids = [pid]
    try:
        pids += [int(child) for child in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except OSError:
        pass
    for each in pids:
        try:
            fields = Path(f"/proc/{each}/stat").read_text().rsplit(")", 1)[1].split()
            total += (int(fields[11]) + int(fields[12])) / ticks
        except (OSError, IndexError, ValueError):
            pass
    return total


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rate", type=float, default=20_000.0, help="messages a second (default 20000)")
    parser.add_argument("--duration", type=float, default=60.0, help="seconds of sending (default 60)")
    parser.add_argument("--domain", type=int, default=150 + os.getpid() % 80, help="ROS_DOMAIN_ID")
    parser.add_argument("--via-rotel", action="store_true", help="through a real collector (rotel)")
    args = parser.parse_args()
    env = {
        **os.environ,
        "ROS_DOMAIN_ID": str(args.domain),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "RCUTILS_COLORIZED_OUTPUT": "0",
    }
    env.pop("ROS_LOCALHOST_ONLY", None)
    receiver = OtlpReceiver(keep=False)
    folder = Path(tempfile.mkdtemp(prefix="ship-bench-"))
    collector = None
    url = receiver.url
    if args.via_rotel:
        from support.rotel import Rotel

        collector = Rotel(receiver.url, folder)
        url = collector.url
    publisher = Child(["--role", "publisher", "--index", "0"], env)
    ship = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "console_tui",
            "ship",
            url,
            "--topic",
            TOPIC,
            "--spool",
            str(folder / "spool"),
            "--robot",
            "bench",
            "--status-every",
            "1",
        ],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        env=env,
        text=True,
    )
    try:
        publisher.expect("ready")
        publisher.ask("matched", cmd="matched", count=1, timeout=60)
        time.sleep(1.0)  # the shipper's intake matched: its subscription and the publisher's
        before = receiver.count()
        cpu_before = process_tree_cpu(ship.pid)
        started = time.monotonic()
        publisher.send(cmd="go", rate=args.rate, duration=args.duration)
        done = publisher.expect("done", args.duration + 120)
        sent = int(done["sent"]) + before
        deadline = time.monotonic() + 120
        steady = 0
        while receiver.count() < sent and time.monotonic() < deadline and steady < 30:
            before_wait = receiver.count()
            time.sleep(0.1)
            steady = steady + 1 if receiver.count() == before_wait else 0  # 3 s without a record: all in
        all_in = min(time.monotonic() - started, float(done["elapsed"]) + 5)
        cpu = process_tree_cpu(ship.pid) - cpu_before
        received = receiver.count()
    finally:
        publisher.close()
        ship.terminate()
        stderr = ship.communicate(timeout=30)[1]
        if collector is not None:
            collector.stop()
        receiver.close()
    lost = max(sent - received, 0)
    last = [line for line in stderr.splitlines() if "sent" in line][-1:]
    print(machine_line())
    print()
    print(
        "| rate offered | seconds | published | received | lost | shipper CPU (cores, while sending) | CPU per message |"
    )
    print("|---|---|---|---|---|---|---|")
    seconds = float(done["elapsed"])
    print(
        f"| {args.rate:,.0f}/s{' via rotel' if collector else ''} | {seconds:.0f} | {sent:,} | {received:,} | "
        f"{lost:,} | {cpu / max(all_in, 1e-9):.2f} | {cpu / max(received, 1) * 1e6:.1f} µs |"
    )
    print()
    print("The shipper said at the end:", re.sub(r"^console-tui ship: ", "", last[0]) if last else "(nothing)")


if __name__ == "__main__":
    main()
