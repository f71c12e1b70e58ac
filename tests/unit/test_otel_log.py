"""The mapping of a record to an OpenTelemetry log record and back: every level exact, other
sources' severities and attributes read sensibly (no network, no protobuf)."""

from __future__ import annotations

import pytest

from console_tui.model.formats.otel_log import (
    OtelLog,
    from_otel,
    level_from_otel,
    line_number,
    otel_logs_of,
    otel_severity,
    to_otel,
)
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns


@pytest.mark.parametrize(
    ("level", "number", "text"),
    [(10, 5, "DEBUG"), (20, 9, "INFO"), (30, 13, "WARN"), (40, 17, "ERROR"), (50, 21, "FATAL"), (25, 11, "25")],
)
def test_ros_levels_are_otel_severities(level, number, text):
    assert otel_severity(level) == (number, text)


def test_every_level_comes_back_exact():
    for level in range(256):
        number, text = otel_severity(level)
        assert 1 <= number <= 24
        assert level_from_otel(number, text) == level


@pytest.mark.parametrize(
    ("number", "text", "level"),
    [
        (1, "TRACE", 10),  # TRACE counts as DEBUG
        (4, "", 10),
        (6, "DEBUG2", 12),
        (9, "", 20),
        (12, "INFO4", 27),
        (13, "Warning", 30),
        (17, "error", 40),
        (24, "", 57),
        (0, "WARNING", 30),  # no number: the text (Python's logging words)
        (0, "critical", 50),
        (0, "notice", 20),
        (0, "", 20),  # neither: INFO
        (0, "ınfo", 20),  # not ASCII: not a word
        (0, "35", 35),
        (99, "ERROR", 40),  # no such number: the text
        (9, "30", 20),  # a decimal text that is not this number's: the number
    ],
)
def test_other_sources_severities(number, text, level):
    assert level_from_otel(number, text) == level


def test_a_ros2_record_and_back():
    record = LogRecord(1_765_000_000_123_456_789, 30, "nav.planner", "no path\nat all", "/src/planner.cpp", "plan", 120)
    log = to_otel(record, host="robot7", robot="picker", observed_ns=5)
    assert log.resource == {"service.name": "nav.planner", "host.name": "robot7", "service.namespace": "picker"}
    assert log.scope_name == "nav.planner"
    assert log.attributes == {
        "code.file.path": "/src/planner.cpp",
        "code.function.name": "plan",
        "code.line.number": 120,
    }
    assert (log.time_unix_nano, log.observed_unix_nano, log.severity_number, log.severity_text) == (
        1_765_000_000_123_456_789,
        5,
        13,
        "WARN",
    )
    back = from_otel(log, source="chdb:///x")
    assert back == LogRecord(
        record.stamp_ns,
        30,
        "nav.planner",
        "no path\nat all",
        "/src/planner.cpp",
        "plan",
        120,
        "chdb:///x",
        robot="picker",
    )


def test_a_ros1_record_keeps_its_topics_and_its_own_robot():
    record = LogRecord(7, 40, "/talker", "m", "talker.py", "cb", 3, topics="/rosout,/chatter", robot="forklift")
    log = to_otel(record, host="h", robot="ignored")
    assert log.resource["service.namespace"] == "forklift"
    assert log.attributes["ros.topics"] == "/rosout,/chatter"
    assert from_otel(log).topics == "/rosout,/chatter"


def test_another_sources_record():
    log = OtelLog(
        0,
        1_700_000_000_000_000_000,  # no Timestamp: the observed one
        0,
        "WARNING",
        "disk full",
        {"host.name": "db-3"},
        "app.storage",
        {"code.filepath": "/srv/app.py", "code.function": "write", "code.lineno": 42},
    )
    record = from_otel(log)
    assert (record.stamp_ns, record.level, record.node, record.robot) == (
        1_700_000_000_000_000_000,
        30,
        "app.storage",
        "db-3",
    )
    assert (record.file, record.function, record.line) == ("/srv/app.py", "write", 42)


@pytest.mark.parametrize(
    ("value", "line"), [(42, 42), ("42", 42), ("+4", 0), (" 4", 0), ("", 0), (True, 0), (-1, 0), (2**32, 0), ("٣", 0)]
)
def test_line_numbers(value, line):
    assert line_number(value) == line


def test_a_batch_in_columns_maps_as_its_records_do():
    records = [
        LogRecord(
            10 + i, [10, 25, 50][i % 3], f"n{i % 2}", f"m{i}", "f.py" if i % 2 else "", "fn", i, robot="r" if i else ""
        )
        for i in range(6)
    ]
    columns = RecordColumns.from_records(records)
    assert otel_logs_of(columns, host="h", robot="default", observed_ns=3) == [
        to_otel(record, host="h", robot="default", observed_ns=3) for record in records
    ]
