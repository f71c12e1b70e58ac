#!/usr/bin/env python3
"""ROS 1 intake benchmark: console-tui's native ROS 1 intake against a rospy subscriber.

A roscpp flood publisher (tests/nodes/roscpp_node.cpp, built with g++) sends
``rosgraph_msgs/Log`` messages (about 170 bytes) on a test topic through a bare
``rosmaster``: as fast as it can ("max") and at fixed rates. In the same run, one after the
other, each subscriber (a fresh process of its own) counts what it receives:

- ``console``: console-tui's ``Ros1LiveSource`` in a thread of the subscriber's process, into
  an ``IntakeQueue`` drained every 50 ms into a ``LogStore`` as the app does;
- ``process``: the same as ``console-tui`` runs it: the live source in the intake process, its
  batches packed onto the pipe, unpacked into the ``IntakeQueue`` and drained into a
  ``LogStore`` (its CPU includes the intake process's);
- ``rospy``: ``rospy.Subscriber`` with a callback that counts, rqt_console's pattern (the
  system Python, where Debian's rospy imports);
- ``discard`` (only when asked for): the ``console`` source's sockets read as they are, each
  message only counted by its length prefix, nothing decoded or stored: about the most any
  subscriber could get from this publisher on this machine.

Received/s is what a subscriber received over the time its messages arrived; lost is what was
sent and never arrived once everything settled: the messages' numbers (``flood message N``)
missing from what console-tui received (or, for rospy, sent less received). CPU is the
subscriber's CPU time (user + system, of its processes) from its first message to the
report, per message received, less the time spent checking the numbers.

    .venv/bin/python benchmarks/ros1_intake.py                          # the table (about 3 minutes)
    .venv/bin/python benchmarks/ros1_intake.py --repeat 3               # medians of 3
    .venv/bin/python benchmarks/ros1_intake.py --rates max --duration 2 # a quick look
    .venv/bin/python benchmarks/ros1_intake.py --rates 100000 --duration 60 --kinds process
                                                                        # 100,000/s for 60 s, 0 lost?
    .venv/bin/python benchmarks/ros1_intake.py --rates max --threads  # where the CPU goes, thread by thread
    .venv/bin/python benchmarks/ros1_intake.py --rates max --kinds process,rospy,discard --repeat 3
    CONSOLE_TUI_COMPILED_FRAMES=0 .venv/bin/python benchmarks/ros1_intake.py --kinds console
                                                                        # without the frame loop in C
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
SUBSCRIBER = Path(__file__).with_name("_ros1_subscriber.py")
TOPIC = "/console_tui_bench_log"  # as _ros1_subscriber.py subscribes
KINDS = ("console", "process", "rospy")
DEFAULT_RATES = ("max", "20000", "100000")
SYSTEM_PYTHON = "/usr/bin/python3"
LOSSLESS_RATE = 100_000
TARGET_VS_ROSPY = 2.0
SETTLE_S = 1.5


# -- the driver ----------------------------------------------------------------------------------


class Process:
    """A child speaking JSON lines on stdout, read on a thread."""

    def __init__(self, command: list[str], env: dict[str, str]) -> None:
        self.popen = subprocess.Popen(
            command, env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True
        )
        self.events: list[dict[str, Any]] = []
        self._cond = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.popen.stdout is not None
        for line in self.popen.stdout:
            try:
                event = json.loads(line)
            except json.JSONDecodeError:
                continue
            with self._cond:
                self.events.append(event)
                self._cond.notify_all()

    def expect(self, name: str, timeout: float = 60.0, after: int = 0) -> dict[str, Any]:
        deadline = time.monotonic() + timeout
        with self._cond:
            while True:
                found = [e for e in self.events[after:] if e.get("event") == name]
                if found:
                    return found[0]
                left = deadline - time.monotonic()
                if left <= 0 or self.popen.poll() is not None:
                    raise TimeoutError(f"{self.popen.args[:3]} never said {name!r}")
                self._cond.wait(min(left, 0.5))

    def send(self, line: str) -> None:
        assert self.popen.stdin is not None
        self.popen.stdin.write(line + "\n")
        self.popen.stdin.flush()

    def stop(self) -> None:
        try:
            if self.popen.stdin is not None:
                self.popen.stdin.close()
        except OSError:
            pass
        try:
            self.popen.wait(10)
        except subprocess.TimeoutExpired:
            self.popen.kill()
            self.popen.wait(5)


def subscriber_command(kind: str) -> list[str]:
    python = SYSTEM_PYTHON if kind == "rospy" else sys.executable
    return [python, str(SUBSCRIBER), kind]


def one_run(kind: str, rate: str, duration: float, binary: Path, env: dict[str, str]) -> dict[str, Any]:
    from _probe import cpu_by_thread

    subscriber = Process(subscriber_command(kind), env)
    publisher: Process | None = None
    try:
        intake_pid = subscriber.expect("ready").get("intake_pid")
        offered = "0" if rate == "max" else rate
        publisher = Process([str(binary), "flood", TOPIC, offered, str(duration), "1"], env)
        publisher.expect("matched", timeout=30)
        roles = {
            "publisher": [publisher.popen.pid],
            "subscriber": [subscriber.popen.pid],
            "intake": [intake_pid] if intake_pid else [],
        }
        threads_before = cpu_by_thread(roles)
        done = publisher.expect("done", timeout=duration + 60)
        threads_after = cpu_by_thread(roles)
        sent = done["sent"]
        report: dict[str, Any] = {}
        previous = -1
        settle_until = time.monotonic() + SETTLE_S
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            mark = len(subscriber.events)
            subscriber.send("report")
            report = subscriber.expect("report", after=mark)
            if report["received"] != previous:
                previous = report["received"]
                settle_until = time.monotonic() + SETTLE_S
            elif report["received"] >= sent or time.monotonic() >= settle_until:
                break
            time.sleep(0.2)
        received = report["received"]
        lost = max(0, sent - received)
        if "missing" in report:  # by the messages' numbers
            lost = report["missing"] + max(sent - report["next"], 0)
        return {
            "kind": kind,
            "rate": rate,
            "sent": sent,
            "received": received,
            "per_s": received / report["seconds"] if report["seconds"] > 0 else 0.0,
            "lost": lost,
            "repeated": report.get("repeated", 0),
            "cpu_us": report["cpu"] / received * 1e6 if received else 0.0,
            "problem": report.get("problem", ""),
            "path": report.get("path", ""),
            "threads": {key: threads_after[key] - threads_before.get(key, 0.0) for key in threads_after},
            "seconds": done["seconds"],
        }
    finally:
        if publisher is not None:
            publisher.stop()
        subscriber.stop()


def main_driver(args: argparse.Namespace) -> int:
    sys.path.insert(0, str(Path(__file__).parent))
    sys.path.insert(0, str(ROOT / "tests"))
    from _probe import threads_table as cpu_table
    from _report import machine_line, table, verdict

    from support.ros1 import build_roscpp_node, free_port, ros1_environment, ros1_missing, roscpp_missing

    reason = ros1_missing() or roscpp_missing()
    if reason:
        print(f"cannot run: {reason}", file=sys.stderr)
        return 2
    binary = build_roscpp_node(ROOT / ".pytest_cache" / "d" / "roscpp_node")
    rates = [rate.strip() for rate in args.rates.split(",") if rate.strip()]
    kinds = [kind.strip() for kind in args.kinds.split(",") if kind.strip()]
    print(machine_line())
    with tempfile.TemporaryDirectory(prefix="console-tui-ros1-bench-") as folder:
        port = free_port()
        env = ros1_environment(Path(folder), port)
        master = subprocess.Popen(
            ["rosmaster", "--core", "-p", str(port)],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )
        try:
            time.sleep(2.0)
            results: dict[tuple[str, str], list[dict[str, Any]]] = {}
            for rate in rates:
                for _ in range(args.repeat):
                    for kind in kinds:
                        result = one_run(kind, rate, args.duration, binary, env)
                        results.setdefault((rate, kind), []).append(result)
                        print(
                            f"  {kind:8} {rate:>6}/s: sent {result['sent']:,}, received {result['received']:,} "
                            f"({result['per_s']:,.0f}/s, {result['lost']:,} lost, {result['repeated']:,} repeated), "
                            f"{result['cpu_us']:.2f} us CPU a message {result['path']} {os.getloadavg()[0]:.1f} load",
                            file=sys.stderr,
                            flush=True,
                        )
        finally:
            master.terminate()
            try:
                master.wait(10)
            except subprocess.TimeoutExpired:
                master.kill()
                master.wait(5)
    rows = []
    for rate in rates:
        cells = {kind: _median(results[(rate, kind)]) for kind in kinds}
        console, rospy = cells.get("process") or cells.get("console"), cells.get("rospy")
        ratio = console["per_s"] / rospy["per_s"] if console and rospy and rospy["per_s"] else 0.0
        row: list[object] = [f"{int(rate):,}" if rate.isdigit() else "as fast as it can"]
        for kind in kinds:
            cell = cells[kind]
            row.append(f"{cell['per_s']:,.0f} ({_lost(cell)})")
        for kind in kinds:
            row.append(f"{cells[kind]['cpu_us']:.2f}")
        row.append(f"{ratio:.2f}x" if ratio else "")
        if rate == "max":
            row.append(verdict(ratio >= TARGET_VS_ROSPY, f"{ratio:.2f}x < {TARGET_VS_ROSPY}x"))
        elif rate.isdigit() and int(rate) == LOSSLESS_RATE and console:
            row.append(verdict(console["lost"] == 0, f"{console['lost']:,} lost"))
        else:
            row.append("")
        if console and rospy:
            row.append(verdict(console["cpu_us"] < rospy["cpu_us"], "more CPU a message than rospy"))
        rows.append(row)
    headers = [
        "offered/s",
        *(f"{kind} received/s (lost)" for kind in kinds),
        *(f"{kind} us CPU/msg" for kind in kinds),
        "console-tui ÷ rospy",
        f"target: ≥ {TARGET_VS_ROSPY}x at max, 0 lost at {LOSSLESS_RATE:,}/s",
        "target: CPU/msg below rospy",
    ]
    compared = "process" if "process" in kinds else "console"
    print(f"\nROS 1 intake, {args.duration:g} s a run, median of {args.repeat} (console-tui: {compared}):\n")
    print(table(headers[: len(rows[0])] if rows else headers, rows))
    if args.threads:
        for (rate, kind), runs in results.items():
            run = _median(runs)
            print(f"\nWhere the CPU went while sending ({kind}, {rate}/s, the median run):\n")
            print(cpu_table(run["threads"], run["seconds"], run["received"]))
    return 0


def _median(runs: list[dict[str, Any]]) -> dict[str, Any]:
    ordered = sorted(runs, key=lambda r: r["per_s"])
    middle = ordered[len(ordered) // 2]
    return {**middle, "cpu_us": statistics.median(r["cpu_us"] for r in runs)}


def _lost(cell: dict[str, Any]) -> str:
    if cell["lost"] < cell["sent"] / 100:
        return f"{cell['lost']:,}"
    return f"{cell['lost'] / cell['sent']:.0%}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rates", default=",".join(DEFAULT_RATES), help="comma-separated: max and/or messages/s")
    parser.add_argument(
        "--kinds",
        default=",".join(KINDS),
        help="subscribers: console, process, rospy; discard (the sockets read, each message only "
        "counted: about the most any subscriber could get from the publisher)",
    )
    parser.add_argument("--duration", type=float, default=5.0, help="seconds the publisher floods (default 5)")
    parser.add_argument("--repeat", type=int, default=1, help="runs per cell, the median shown (default 1)")
    parser.add_argument("--threads", action="store_true", help="where the CPU went, thread by thread, while sending")
    return main_driver(parser.parse_args())


if __name__ == "__main__":
    raise SystemExit(main())
