"""A message both a rosout log (or a ROS 2 launch log) and its node's own log file hold is one
record (issue 28); every other repeat stays as it is (no files needed: the merger reads records
and each file's kind)."""

from __future__ import annotations

from types import SimpleNamespace

from console_tui.model.store.record import LogRecord
from console_tui.sources.files.repeats import TOLERANCE_NS, RepeatMerger

T = 1_700_000_000_000_000_000
MS = 1_000_000
FILES = [
    SimpleNamespace(source="rosout.log", kind="rosout"),
    SimpleNamespace(source="talker-1-stdout.log", kind="ros1-console"),
    SimpleNamespace(source="other-2-stdout.log", kind="ros1-console"),
    SimpleNamespace(source="saved.csv", kind="rqt"),
]
LAUNCH = SimpleNamespace(source="run/launch.log", kind="launch")
NODE_FILE = SimpleNamespace(source="talker_4242_1700000000000.log", kind="rcutils")


def rec(ms: float, source: str, msg: str = "hello", node: str = "/talker", **fields) -> LogRecord:
    return LogRecord(T + int(ms * MS), 20, node, msg, source=source, **fields)


def merged(records: list[LogRecord], files=FILES, batch: int = 2) -> tuple[list[tuple], int]:
    merger = RepeatMerger()
    batches = [records[i : i + batch] for i in range(0, len(records), batch)]
    out = [r for b in merger.merge(batches, files) for r in b]  # type: ignore[arg-type]
    return [((r.stamp_ns - T) / MS, r.source, r.msg, r.file) for r in out], merger.merged


def test_the_rosout_copy_is_kept_naming_both_files():
    rows, count = merged(
        [
            rec(0, "talker-1-stdout.log"),
            rec(0.8, "rosout.log", file="talker.py"),
            rec(5, "rosout.log", "bye", file="talker.py"),
            rec(5.001, "talker-1-stdout.log", "bye"),
        ]
    )
    assert rows == [
        (0.8, "rosout.log + talker-1-stdout.log", "hello", "talker.py"),
        (5, "rosout.log + talker-1-stdout.log", "bye", "talker.py"),
    ]
    assert count == 2


def test_a_message_logged_twice_stays_two_rows_and_other_repeats_stay():
    records = [
        rec(0, "rosout.log"),
        rec(0.5, "talker-1-stdout.log"),
        rec(1, "rosout.log"),  # logged again 1 ms later: its own pair
        rec(1.5, "talker-1-stdout.log"),
        rec(2, "rosout.log"),  # in rosout.log only
        rec(3, "talker-1-stdout.log", node="talker", msg="x"),
        rec(3, "other-2-stdout.log", node="talker", msg="x"),  # two node files: both stay
        rec(4, "saved.csv", msg="y"),
        rec(4, "rosout.log", msg="y"),  # a save is no node log: both stay
        rec(10 + TOLERANCE_NS / MS, "talker-1-stdout.log"),  # too far from the one at 2 ms
    ]
    rows, count = merged(records)
    assert count == 2
    assert [source for _, source, _, _ in rows] == [
        "rosout.log + talker-1-stdout.log",
        "rosout.log + talker-1-stdout.log",
        "rosout.log",
        "talker-1-stdout.log",
        "other-2-stdout.log",
        "saved.csv",
        "rosout.log",
        "talker-1-stdout.log",
    ]


def test_other_severities_nodes_and_robots_are_other_messages():
    records = [
        rec(0, "rosout.log"),
        LogRecord(T, 30, "/talker", "hello", source="talker-1-stdout.log"),
        rec(1, "rosout.log", node="/listener"),
        rec(1, "talker-1-stdout.log", robot="picker"),
    ]
    rows, count = merged(records)
    assert count == 0 and len(rows) == 4


def test_without_both_kinds_of_file_the_batches_pass_as_they_are():
    batches = [[rec(0, "rosout.log"), rec(0, "rosout.log")]]
    assert RepeatMerger().merge(batches, FILES[:1]).__next__() is batches[0]  # type: ignore[arg-type]


def test_a_launch_logs_copy_and_the_nodes_file_are_one_row_the_launch_copy_kept():
    """ROS 2: launch.log holds each node's console line, stamp and all, and the node's own log
    file the same message: one row, named for both (``--last`` opens both)."""
    records = [
        rec(0, "talker_4242_1700000000000.log"),
        rec(0, "run/launch.log"),
        rec(1, "run/launch.log", "printed\nand a line printed after it"),  # not the same text: both stay
        rec(1, "talker_4242_1700000000000.log", "printed"),
        rec(2, "run/launch.log", "only launch"),
    ]
    rows, count = merged(records, files=[LAUNCH, NODE_FILE])
    assert count == 1
    assert [(ms, source) for ms, source, _, _ in rows] == [
        (0, "run/launch.log + talker_4242_1700000000000.log"),
        (1, "run/launch.log"),
        (1, "talker_4242_1700000000000.log"),
        (2, "run/launch.log"),
    ]


def test_a_rosout_a_launch_and_a_node_copy_are_one_row_the_rosout_copy_kept():
    records = [
        rec(0, "talker_4242_1700000000000.log"),
        rec(0, "run/launch.log"),
        rec(0.7, "rosout.log", file="talker.py"),
        rec(3, "run/launch.log", "twice"),
        rec(3, "run/launch.log", "twice"),  # logged twice: two rows, each with its rosout copy
        rec(3.4, "rosout.log", "twice", file="talker.py"),
        rec(3.5, "rosout.log", "twice", file="talker.py"),
    ]
    rows, count = merged(records, files=[FILES[0], LAUNCH, NODE_FILE], batch=3)
    assert count == 4
    assert rows == [
        (0.7, "rosout.log + run/launch.log + talker_4242_1700000000000.log", "hello", "talker.py"),
        (3.4, "rosout.log + run/launch.log", "twice", "talker.py"),
        (3.5, "rosout.log + run/launch.log", "twice", "talker.py"),
    ]
