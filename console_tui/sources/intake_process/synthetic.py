"""Made-up log records at a steady rate: the intake process's stand-in for ROS, so that the
screen benchmark and tests without ROS exercise the same hand-off (pipe, batches, status)."""

from __future__ import annotations

import threading
import time
from dataclasses import replace

from ...model.store.intake_queue import IntakeQueue
from ...model.store.record import LogRecord
from ...model.store.record_batch import RecordColumns
from ..status import SourceStatus

PERIOD_S = 0.02
_NODES = ["navigation.planner", "navigation.controller", "sensors.lidar_driver", "perception.camera", "power.battery"]
_LEVELS = [20, 20, 20, 10, 30, 20, 20, 40, 20, 50]
_TEXTS = [
    "Planned path to ({0}.50, -2.25): {1} poses, 2.1 m",
    "costmap updated: 0.05 m/cell, {1} obstacles",
    "planner failed to find a path within 0.5 s, retrying with relaxed tolerance ({0})",
    "scan {0}: 720 points, 0.{1} ms",
    "battery 24.{1} V, 81%, message {0}",
]
START_NS = 1_795_000_000_000_000_000


def synthetic_record(number: int) -> LogRecord:
    node = _NODES[number % len(_NODES)]
    return LogRecord(
        START_NS + number * 50_000,
        _LEVELS[number % len(_LEVELS)],
        node,
        _TEXTS[number % len(_TEXTS)].format(number, number % 997),
        f"/opt/robot/src/{node.split('.')[-1]}.cpp",
        ["plan", "update", "on_timer", "publish_scan", "tick"][number % 5],
        40 + number % 300,
        "synthetic",
    )


class SyntheticSource:
    """Puts ``rate`` records a second into ``queue`` (in batches every ``PERIOD_S``), from
    record number ``first``; ``count`` records in all, or until stopped."""

    def __init__(self, queue: IntakeQueue, rate: float, *, count: int | None = None) -> None:
        self.queue = queue
        self.rate = rate
        self.count = count
        self.status = SourceStatus(topic="synthetic", publishers=1, path="synthetic")
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def start(self) -> None:
        self._thread = threading.Thread(target=self._run, name="console-tui-synthetic", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(2.0)

    def _run(self) -> None:
        self.status = replace(self.status, running=True)
        made = 0
        began = time.monotonic()
        while not self._stop.wait(PERIOD_S):
            due = int((time.monotonic() - began) * self.rate)
            if self.count is not None:
                due = min(due, self.count)
            if due > made:
                self.queue.put(RecordColumns.from_records([synthetic_record(number) for number in range(made, due)]))
                made = due
            lost = self.queue.dropped
            if lost != self.status.lost:
                self.status = replace(self.status, lost=lost, lost_queue=lost)
        self.status = replace(self.status, running=False)
