"""Deterministic records for UI tests and snapshots: fixed stamps, every severity."""

from __future__ import annotations

from console_tui.model.loggers.logger_levels import GraphNode
from console_tui.model.store.record import LogRecord
from console_tui.sources.status import SourceStatus

BASE_NS = 1_795_000_000_000_000_000  # a fixed moment; snapshot tests show it in UTC

NODES = [
    "count_and_log",
    "navigation.planner",
    "navigation.planner.costmap",
    "sensors.lidar_driver",
    "power.battery_monitor",
]
LEVELS = [20, 20, 30, 20, 10, 40, 20, 20, 30, 50]
TEXTS = [
    "Planned path to (1.50, -2.25): 32 poses, 2.1 m",
    "costmap updated: 0.05 m/cell, 412 obstacles",
    "planner failed to find a path within 0.5 s, retrying with relaxed tolerance",
    "scan {i}: 720 points, 0.6 ms",
    "Counted to {i}",
    "Timed out waiting for costmap update after 1.2 s",
    "battery 24.3 V, 81%",
    "diagnostics:\n  temperature: 41.2 C\n  motor: 600 rpm",
    "dropped 3 packets from 192.0.2.10: checksum mismatch",
    "{i} is divisible by 20",
]


def record(i: int) -> LogRecord:
    return LogRecord(
        stamp_ns=BASE_NS + i * 137_000_000,
        level=LEVELS[i % len(LEVELS)],
        node=NODES[i % len(NODES)],
        msg=TEXTS[i % len(TEXTS)].format(i=i),
        file=f"/opt/robot/src/{NODES[i % len(NODES)].split('.')[-1]}.cpp",
        function=["plan", "update", "on_timer", "publish_scan", "tick"][i % 5],
        line=40 + (i * 7) % 300,
        source="/rosout",
    )


def records(count: int, start: int = 0) -> list[LogRecord]:
    return [record(i) for i in range(start, start + count)]


# -- the logger levels pane, fed as its LoggerControl would feed it ---------------------------

PLANNER = "/navigation/planner"
GRAPH = (
    GraphNode("/", "count_and_log", True),
    GraphNode("/navigation", "planner", True),
    GraphNode("/power", "battery_monitor", False),
    GraphNode("/sensors", "lidar_driver", False),
)
PLANNER_LEVELS = {"navigation.planner": 10, "navigation.planner.costmap": 0, "navigation": 0, "": 20}


def feed_logger_pane(pane) -> None:
    """Four nodes (one without logger services, one still being checked), the planner selected."""
    pane.show_nodes(GRAPH, checking={"/sensors/lidar_driver"})
    pane.select_node(PLANNER)
    pane.show_levels(PLANNER, PLANNER_LEVELS)


class StaticSource:
    """A live source as the app sees one (``start``, ``stop``, a ``status`` snapshot) that
    sends nothing: its status is what a test sets."""

    def __init__(self, status: SourceStatus) -> None:
        self.status = status

    def start(self) -> None:
        pass

    def stop(self) -> None:
        pass
