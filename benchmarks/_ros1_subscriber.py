#!/usr/bin/env python3
"""The subscribers of ``ros1_intake.py``, each run as a process of its own by it.

    python benchmarks/_ros1_subscriber.py console|process|rospy|discard

``console``: console-tui's ``Ros1LiveSource`` in a thread of this process; ``process``: the
same in the intake process, as ``console-tui`` runs it; ``rospy``: a ``rospy.Subscriber``
(the system Python, where Debian's rospy imports); ``discard``: the ``console`` source's
sockets read by its loop at its pace, but each message only counted (its length prefix
skipped over), nothing decoded or stored: about the most any subscriber gets from the
publisher. Each says ``ready``, then answers every ``report`` line on stdin with what it
received (JSON lines on stdout), and ends when stdin closes.
"""

from __future__ import annotations

import json
import os
import sys
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
TOPIC = "/console_tui_bench_log"
KINDS = ("console", "process", "rospy", "discard")
DRAIN_S = 0.05


def say(**fields: Any) -> None:
    print(json.dumps(fields), flush=True)


# -- the subscriber processes ------------------------------------------------------------------


class Commands:
    """Lines from stdin ("report"), read on a thread; ``closed`` once stdin ends."""

    def __init__(self) -> None:
        self.report = threading.Event()
        self.closed = threading.Event()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        for line in sys.stdin:
            if line.strip() == "report":
                self.report.set()
        self.closed.set()


def cpu_seconds() -> float:
    times = os.times()
    return times.user + times.system


class Numbers:
    """The flood's message numbers seen (``flood message N: ...``), in order: what is missing."""

    def __init__(self) -> None:
        self.next = 0
        self.missing = 0
        self.repeated = 0
        #: This thread's CPU seconds spent here (not the intake's: left out of its CPU).
        self.cpu = 0.0

    def see(self, msgs: Any) -> None:
        began = time.thread_time()
        for msg in msgs:
            number = int(msg[14 : msg.index(":", 14)])
            if number >= self.next:
                self.missing += number - self.next
                self.next = number + 1
            else:
                self.repeated += 1
        self.cpu += time.thread_time() - began

    def lost(self, sent: int) -> int:
        return self.missing + max(sent - self.next, 0)


def run_console(kind: str) -> None:
    sys.path.insert(0, str(ROOT))
    sys.path.insert(0, str(Path(__file__).parent))
    from _probe import process_cpu

    from console_tui.model.store.intake_queue import IntakeQueue
    from console_tui.model.store.log_store import LogStore
    from console_tui.sources.intake_process.parent import ProcessSource
    from console_tui.sources.ros1.live_source import Ros1LiveSource

    discarded = [0]
    if kind == "discard":
        from console_tui.model.formats.ros1_log_msg import Ros1LogDecoder

        def count_frames(_self: Any, buffer: bytes, start: int, *_args: Any, **_kwargs: Any) -> int:
            pos, end, count = start, len(buffer), 0
            while pos + 4 <= end:
                after = pos + 4 + int.from_bytes(buffer[pos : pos + 4], "little")
                if after > end:
                    break
                pos, count = after, count + 1
            discarded[0] += count
            return pos

        Ros1LogDecoder.decode_frames = count_frames  # type: ignore[method-assign]
        from console_tui.sources.coalesce import Coalescer

        paced_by = Coalescer.after
        counted = [0]

        def after(self: Coalescer, _taken: int) -> float:  # the turn's messages, as counted
            taken, counted[0] = discarded[0] - counted[0], discarded[0]
            return paced_by(self, taken)

        Coalescer.after = after  # type: ignore[method-assign]

    queue = IntakeQueue()
    store = LogStore()
    source: Any = ProcessSource(queue, "ros1", topic=TOPIC) if kind == "process" else Ros1LiveSource(queue, topic=TOPIC)
    source.start()
    deadline = time.monotonic() + 30
    while kind == "process" and source.pid is None and time.monotonic() < deadline:
        time.sleep(0.01)

    def cpu() -> float:
        pid = getattr(source, "pid", None)
        return cpu_seconds() + (process_cpu(pid) if pid else 0.0)

    commands = Commands()
    say(event="ready", intake_pid=getattr(source, "pid", None))
    first_at = last_at = cpu_at_first = 0.0
    # Every message drained counts: the store keeps at most its cap (1,000,000), fewer than a
    # run at the publisher's maximum sends.
    received = 0
    numbers = Numbers()
    while not commands.closed.is_set():
        batches = queue.drain_batches()  # as the app does
        if batches:
            now = time.monotonic()
            if not first_at:
                first_at, cpu_at_first = now, cpu()
            last_at = now
            for batch in batches:
                received += len(batch)
                store.extend(batch)
                numbers.see(batch.msgs)
        if kind == "discard" and discarded[0] != received:
            now = time.monotonic()
            if not first_at:
                first_at, cpu_at_first = now, cpu()
            last_at, received = now, discarded[0]
        if commands.report.is_set():
            commands.report.clear()
            status = source.status
            # By the messages' numbers, where they were read (discard reads none).
            by_numbers = {} if kind == "discard" else {"missing": numbers.missing, "next": numbers.next}
            say(
                event="report",
                received=received,
                seconds=last_at - first_at,
                cpu=cpu() - cpu_at_first - numbers.cpu,
                lost_counted=status.lost,
                problem=status.problem,
                path=status.path,
                repeated=numbers.repeated,
                **by_numbers,
            )
        time.sleep(DRAIN_S)
    source.stop()


def run_rospy() -> None:
    import rospy
    from rosgraph_msgs.msg import Log

    rospy.init_node("rospy_bench_subscriber", disable_signals=True)
    counts = {"received": 0, "first": 0.0, "last": 0.0, "cpu": 0.0}

    def callback(_message: Any) -> None:
        now = time.monotonic()
        if not counts["received"]:
            counts["first"], counts["cpu"] = now, cpu_seconds()
        counts["received"] += 1
        counts["last"] = now

    rospy.Subscriber(TOPIC, Log, callback)  # as rqt_console subscribes
    commands = Commands()
    say(event="ready")
    while not commands.closed.wait(DRAIN_S):
        if commands.report.is_set():
            commands.report.clear()
            say(
                event="report",
                received=counts["received"],
                seconds=counts["last"] - counts["first"],
                cpu=cpu_seconds() - counts["cpu"],
                lost_counted=0,
                problem="",
            )
    rospy.signal_shutdown("done")


def main() -> int:
    kind = sys.argv[1] if len(sys.argv) == 2 else ""
    if kind in ("console", "process", "discard"):
        run_console(kind)
    elif kind == "rospy":
        run_rospy()
    else:
        print(f"usage: {sys.argv[0]} {'|'.join(KINDS)}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
