"""Journal entries (``journalctl -o json``'s lines) as records: no journald, no ROS."""

from __future__ import annotations

import json

import pytest

from console_tui.model.formats.journal_entry import (
    MAX_ENTRY_BYTES,
    MAX_MESSAGE_CHARS,
    PRIORITY_LEVELS,
    JournalEntries,
    field_text,
)

STAMP = {"__REALTIME_TIMESTAMP": "1765000000123456"}


def read(entry: dict, **options) -> object:
    return JournalEntries(**options).line(json.dumps({**STAMP, **entry}))


@pytest.mark.parametrize(
    ("priority", "level"),
    [("0", 50), ("1", 50), ("2", 50), ("3", 40), ("4", 30), ("5", 20), ("6", 20), ("7", 10)],
)
def test_syslog_priorities_are_levels(priority, level):
    record = read({"MESSAGE": "m", "PRIORITY": priority})
    assert record.level == level and PRIORITY_LEVELS[int(priority)] == level


def test_an_entry_without_priority_is_info_and_its_node_falls_back_from_identifier_to_unit():
    assert read({"MESSAGE": "m"}).level == 20
    assert read({"MESSAGE": "m", "SYSLOG_IDENTIFIER": "planner", "_COMM": "python3"}).node == "planner"
    assert read({"MESSAGE": "m", "_COMM": "python3", "_SYSTEMD_UNIT": "nav.service"}).node == "python3"
    assert read({"MESSAGE": "m", "_SYSTEMD_UNIT": "nav.service"}).node == "nav.service"
    assert read({"MESSAGE": "m", "_SYSTEMD_USER_UNIT": "mine.service"}).node == "mine.service"
    assert read({"MESSAGE": "m"}).node == "journal"


def test_location_time_and_host():
    record = read(
        {
            "MESSAGE": "planned",
            "CODE_FILE": "/src/nav.py",
            "CODE_FUNC": "plan",
            "CODE_LINE": "42",
            "_SOURCE_REALTIME_TIMESTAMP": "1765000000000001",
            "_HOSTNAME": "robot7",
        },
        robot_from_host=True,
        source="remote-robot7.journal",
    )
    assert (record.file, record.function, record.line) == ("/src/nav.py", "plan", 42)
    assert record.stamp_ns == 1765000000000001000, "when the process logged it, not when journald took it"
    assert record.robot == "robot7" and record.source == "remote-robot7.journal"
    assert read({"MESSAGE": "m", "_HOSTNAME": "robot7"}).robot == "", "this machine's journal names no robot"
    assert read({"MESSAGE": "m", "CODE_LINE": "x" * 30}).line == 0
    assert read({"MESSAGE": "m"}).stamp_ns == 1765000000123456000


def test_rcl_logging_syslog_lines_read_back_as_the_ros_records_they_were():
    """rcl_logging_syslog: syslog(priority, "%s", the line RCUTILS_CONSOLE_OUTPUT_FORMAT made),
    identifier the executable, facility LOCAL1 (17)."""
    entries = JournalEntries()
    record = entries.line(
        json.dumps(
            {
                **STAMP,
                "MESSAGE": "[WARN] [1765000000.000000007] [nav.planner]: no path from (0, 0)",
                "PRIORITY": "4",
                "SYSLOG_IDENTIFIER": "planner_node",
                "SYSLOG_FACILITY": "17",
            }
        )
    )
    assert (record.level, record.node, record.msg, record.stamp_ns) == (
        30,
        "nav.planner",
        "no path from (0, 0)",
        1765000000000000007,
    )
    assert entries.ros_records == 1
    # FATAL travels as LOG_ALERT (1): the line's own level wins either way.
    assert read({"MESSAGE": "[FATAL] [1.5] [x]: gone", "PRIORITY": "1"}).level == 50


def test_a_format_with_the_location_gives_file_function_and_line():
    template = "[{severity}] [{time}] [{name}]: {message} ({function_name}() at {file_name}:{line_number})"
    record = read(
        {"MESSAGE": "[ERROR] [1765000000.000000001] [arm]: stuck (move() at /src/arm.cpp:77)"}, template=template
    )
    assert (record.node, record.msg, record.function, record.file, record.line) == (
        "arm",
        "stuck",
        "move",
        "/src/arm.cpp",
        77,
    )
    # the default format has none: the entry's own CODE_ fields, if any
    record = read({"MESSAGE": "[INFO] [1.0] [arm]: ok", "CODE_FILE": "a.cpp", "CODE_LINE": "3"})
    assert (record.file, record.line) == ("a.cpp", 3)


def test_a_launch_run_as_a_unit_reads_back_its_processes_lines():
    record = read({"MESSAGE": "[talker-1] [INFO] [1765000000.500000000] [talker]: Publishing: 'Hello'"})
    assert (record.node, record.msg, record.stamp_ns, record.level) == (
        "talker",
        "Publishing: 'Hello'",
        1765000000500000000,
        20,
    )
    plain = read({"MESSAGE": "[talker-1] a line it printed", "SYSLOG_IDENTIFIER": "ros2"})
    assert (plain.node, plain.msg) == ("ros2", "[talker-1] a line it printed"), "kept as it is"


def test_binary_repeated_and_withheld_fields():
    assert field_text([104, 105, 0xFF]) == "hi\ufffd"
    assert field_text(["first", "second"]) == "first"
    assert field_text(None) is None and field_text(7) is None
    entries = JournalEntries()
    assert entries.line(json.dumps({**STAMP, "MESSAGE": None})) is None  # over 4,096 bytes without --all
    assert entries.line(json.dumps({**STAMP})) is None
    assert entries.without_message == 2
    record = entries.line(json.dumps({**STAMP, "MESSAGE": [27, 91, 50, 74, 10]}))
    assert record.msg == "\x1b[2J", "kept as text: the record path shows it inert"


def test_bounded_lines_and_messages():
    entries = JournalEntries()
    assert entries.line(b"x" * (MAX_ENTRY_BYTES + 1)) is None
    assert entries.line(b"not json") is None and entries.line(b"[1, 2]") is None
    assert entries.unreadable == 3
    long = read({"MESSAGE": "y" * (MAX_MESSAGE_CHARS + 10)})
    assert long.msg.startswith("y" * MAX_MESSAGE_CHARS) and long.msg.endswith("[cut: 10 more characters]")
    assert read({"MESSAGE": "two\nlines\n"}).msg == "two\nlines"
