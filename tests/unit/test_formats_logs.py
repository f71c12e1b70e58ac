"""ROS 2 log lines (rcutils formats), ROS 1 rosout.log, detection, and atomic saves."""

from __future__ import annotations

import os

import pytest

from console_tui.model.formats import (
    FormatError,
    RcutilsLogFormat,
    RosoutLogFormat,
    SaveCancelled,
    detect_text_format,
    save_records,
    text_formats,
)
from console_tui.model.formats.rcutils_log import decode_template, split_template

from support.formats import hostile_records, read_cleanly, read_text

DEFAULT_LOG = (
    b"[INFO] [1795345407.868935159] [ns.probe]: hello\n"
    b"[WARN] [1795345407.869679808] [ns.probe]: multi\n"
    b'line "quoted"; semi\n'
    b"\n"
    b"[ERROR] [1795345407.870191636] [ns.probe]: na\xc3\xafve \xe2\x9c\x93\n"
    b"[DEBUG] [0000000001.000000001] [ns.probe.kid]: [INFO] not a header mid-line\n"
)


def test_default_rcutils_format_with_multi_line_messages():
    records = read_cleanly(DEFAULT_LOG, RcutilsLogFormat(), "node.log")
    assert [(r.level, r.node, r.msg) for r in records] == [
        (20, "ns.probe", "hello"),
        (30, "ns.probe", 'multi\nline "quoted"; semi\n'),
        (40, "ns.probe", "naïve ✓"),
        (10, "ns.probe.kid", "[INFO] not a header mid-line"),
    ]
    assert records[0].stamp_ns == 1795345407_868935159
    assert records[3].stamp_ns == 1_000_000_001


CUSTOM = "{time_as_nanoseconds} {severity} {name} {function_name} {file_name}:{line_number} | {message} | end"


def test_custom_template_with_every_location_token():
    data = (
        b"1795345408542813893 INFO ns.probe <module> /tmp/n.py:6 | hello | end\n"
        b"1795345408543451033 WARN ns.probe tick /tmp/n.py:7 | multi\n"
        b"line | still\n"
        b" | end\n"
    )
    records = read_cleanly(data, RcutilsLogFormat(CUSTOM), "n.log")
    assert [(r.stamp_ns, r.level, r.node, r.function, r.file, r.line, r.msg) for r in records] == [
        (1795345408542813893, 20, "ns.probe", "<module>", "/tmp/n.py", 6, "hello"),
        (1795345408543451033, 30, "ns.probe", "tick", "/tmp/n.py", 7, "multi\nline | still\n"),
    ]


def test_template_parsing_follows_rcutils():
    assert decode_template(r"a\tb\nc\x1b[0m\q") == "a\tb\nc\x1b[0m\\q"
    assert split_template("{{severity}} {unknown} {message}") == [
        (False, "{"),
        (True, "severity"),
        (False, "} {unknown} "),
        (True, "message"),
    ]


def test_date_time_template_and_colour_codes():
    template = "[{severity}] [{date_time_with_ms}] [{name}]: {message}"
    data = b"\x1b[33m[WARN] [2026-11-22 11:03:28.542] [n]: coloured\x1b[0m\n"
    records, problems = read_text(data, RcutilsLogFormat(template), "c.log")
    assert list(problems) == [] and records[0].msg == "coloured" and records[0].level == 30
    assert records[0].stamp_ns % 1_000_000_000 == 542_000_000


def test_template_starting_with_the_message_ends_records_at_its_tail():
    records, _ = read_text(b"hello (n)\nmulti\nline (m)\n", RcutilsLogFormat("{message} ({name})"), "x")
    assert [(r.msg, r.node) for r in records] == [("hello", "n"), ("multi\nline", "m")]


def test_rcutils_stray_lines_are_reported_with_line_numbers():
    data = b"garbage before\nmore garbage\n" + DEFAULT_LOG
    records, problems = read_text(data, RcutilsLogFormat(), "node.log")
    assert len(records) == 4
    assert [(p.line, "not a ROS 2 log file record" in p.what) for p in problems] == [(1, True)]


ROSOUT_LOG = (
    b"\n\n1795345770.845885174  Node Startup\n"
    b"1795345776.389451742 INFO /talker1 [talker1.py:11(<module>)] [topics: /rosout, /chatter] hello\n"
    b"1795345776.391536712 WARN /talker1 [talker1.py:12(<module>)] [topics: /rosout] multi\n"
    b'line "quoted"; semi\n'
    b"1795345776.393861532 ERROR /cpp [/src/n.cpp:30(void Node::cb(int))] [topics: ] na\xc3\xafve\n"
    b"1795345776.396429061 FATAL /cpp [/src/n.cpp:31(operator()())] omitted topics\n"
    b"1795345776.396429062 3 /odd [f.py:1(f)] [topics: /rosout] unknown level\n"
)


def test_rosout_log():
    records = read_cleanly(ROSOUT_LOG, RosoutLogFormat(), "rosout.log")
    assert [(r.level, r.node, r.file, r.line, r.function, r.msg) for r in records] == [
        (20, "/talker1", "talker1.py", 11, "<module>", "hello"),
        (30, "/talker1", "talker1.py", 12, "<module>", 'multi\nline "quoted"; semi'),
        (40, "/cpp", "/src/n.cpp", 30, "void Node::cb(int)", "naïve"),
        (50, "/cpp", "/src/n.cpp", 31, "operator()()", "omitted topics"),
        (20, "/odd", "f.py", 1, "f", "unknown level"),
    ]
    assert records[0].stamp_ns == 1795345776_389451742
    assert [r.topics for r in records] == ["/rosout,/chatter", "/rosout", "", "", "/rosout"]


@pytest.mark.parametrize(
    "data, expected",
    [
        (b"message;severity;node;stamp;location\n", "rqt"),
        (b"message;severity;node;stamp;topics;location\n", "rqt"),
        (b'{"stamp_ns": 1, "msg": "m"}\n', "jsonl"),
        (ROSOUT_LOG, "rosout"),
        (DEFAULT_LOG, "rcutils"),
    ],
)
def test_detects_each_text_format(data, expected):
    assert detect_text_format(data, text_formats(), "f").name == expected


@pytest.mark.parametrize(
    "data, message",
    [
        (b"", "the file is empty"),
        (b"\n\n  \n", "no log records (only blank lines)"),
        (bytes(range(256)) * 4, "binary data"),
        (b"\x7fELF\x02\x01\x01\x00" + b"\x00" * 100, "first bytes: 7f 45 4c 46"),
        (b"#ROSBAG V1.2\n", "old version 1.x"),
        (b"just some notes\nnothing like a log\n", "first line is 'just some notes'"),
        (b"name,age\nbob,3\n", "known formats: rqt_console CSV; JSON Lines"),
    ],
)
def test_unreadable_files_say_why(data, message):
    with pytest.raises(FormatError) as caught:
        detect_text_format(data, text_formats(), "f.log")
    assert message in str(caught.value) and str(caught.value).startswith("f.log: ")


def test_log_format_option_is_tried_first():
    data = b"1795345408542813893 INFO n f /x.py:1 | hi | end\n"
    with pytest.raises(FormatError):
        detect_text_format(data, text_formats(), "n.log")
    assert detect_text_format(data, text_formats(CUSTOM), "n.log").name == "rcutils"
    assert detect_text_format(data, text_formats(None, (CUSTOM,)), "n.log").name == "rcutils"


def test_text_damage_is_located():
    data = b"[INFO] [1.000000000] [n]: ok\n[INFO] [2.000000000] [n]: bad \xff byte\n[INFO] [3.000000000] [n]: nul \x00\n[INFO] [4.0000"
    records, problems = read_text(data, RcutilsLogFormat(), "n.log")
    # The cut-off last line does not start a record, so it continues the one before.
    assert [r.msg for r in records] == ["ok", "bad \ufffd byte", "nul \x00\n[INFO] [4.0000"]
    by_kind = {p.what.split(" (")[0].split(":")[0]: p for p in problems}
    assert by_kind["bytes that are not UTF-8"].line == 2
    assert "byte 59" in by_kind["bytes that are not UTF-8"].what
    assert by_kind["binary data"].line == 3 and by_kind["binary data"].offset == 96
    assert any(p.line == 4 and "ends in the middle of a line" in p.what for p in problems)


def test_atomic_save_keeps_the_old_file_when_interrupted(tmp_path):
    path = tmp_path / "saved.csv"
    path.write_text("the good old file\n")
    os.chmod(path, 0o640)

    def exploding():
        yield from hostile_records()
        raise RuntimeError("disk on fire")

    with pytest.raises(RuntimeError):
        save_records(exploding(), path)
    assert path.read_text() == "the good old file\n"
    assert os.listdir(tmp_path) == ["saved.csv"]

    class Cancelled:
        def is_set(self):
            return True

    with pytest.raises(SaveCancelled):
        save_records(hostile_records() * 1000, path, cancel=Cancelled())
    assert path.read_text() == "the good old file\n" and os.listdir(tmp_path) == ["saved.csv"]

    assert save_records(hostile_records(), path) == len(hostile_records())
    assert path.read_bytes().startswith(b"message;severity;node;stamp;location\n")
    assert os.stat(path).st_mode & 0o777 == 0o640
    assert os.listdir(tmp_path) == ["saved.csv"]


def test_save_to_a_missing_directory_raises_oserror(tmp_path):
    with pytest.raises(OSError):
        save_records(hostile_records(), tmp_path / "no" / "such" / "x.jsonl")


def test_kinetic_rosout_log_without_a_node_field():
    """Issue 11, item 7: the log4cxx rosout node (Kinetic and before) wrote no node name
    and no ``]`` after the function; such files read as 0 records and a problem a line."""
    data = (
        b"\n\n0.000000000  Node Startup\n"
        b"0.000000000 INFO [/ws/src/map_server/src/main.cpp:167(MapServer) [topics: /rosout] Loading map from image\n"
        b"1487700000.250000000 WARN [/ws/src/n.cpp:12(operator()) [topics: /rosout, /map] two\nlines [/not markup]\n"
        b"1487700001.000000000 ERROR [n.py:3(<module>) [topics: ] empty topics\n"
    )
    records = read_cleanly(data, RosoutLogFormat(), "rosout.log")
    assert [(r.stamp_ns, r.level, r.node, r.file, r.function, r.line, r.msg) for r in records] == [
        (0, 20, "", "/ws/src/map_server/src/main.cpp", "MapServer", 167, "Loading map from image"),
        (1487700000_250000000, 30, "", "/ws/src/n.cpp", "operator()", 12, "two\nlines [/not markup]"),
        (1487700001_000000000, 40, "", "n.py", "<module>", 3, "empty topics"),
    ]
