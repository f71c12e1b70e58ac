"""rqt_console CSV and JSON Lines: byte-exact rqt files, round trips, bad rows."""

from __future__ import annotations

import io
import json

import pytest

from console_tui.model.formats import JsonLinesFormat, RqtCsvFormat, save_records
from console_tui.model.formats.jsonl import JsonLinesWriter
from console_tui.model.formats.rqt_csv import RqtCsvWriter, split_location
from console_tui.model.store.record import LogRecord

from support.formats import DATA, fields, hostile_records, read_cleanly, read_text


def _write(writer, records) -> bytes:
    stream = io.BytesIO()
    for _ in writer.write(records, stream):
        pass
    return stream.getvalue()


def _rec(msg, level, node, stamp, file, function, line, source="rqt_console_ros2.csv"):
    return LogRecord(stamp, level, node, msg, file, function, line, source)


ROS2_EXPECTED = [
    _rec("hello", 20, "talker", 1700000000_000000005, "/ws/src/talker.py", "tick", 42),
    _rec('say "hi"; bye', 30, "ns.talker", 1700000000_100000000, "/ws/src/talker.py", "tick", 43),
    _rec(
        'first line\nsecond "q"\n\nafter a blank line',
        40,
        "ns.talker.child",
        1700000001_000000000,
        "/ws/src/talker.py",
        "on_timer",
        7,
    ),
    _rec("naïve ✓ 日本語", 10, "talker", 1700000001_000000001, "/ws/src/talker.py", "tick", 44),
    _rec("path C:\\dir\\", 50, "talker", 1700000002_999999999, "/ws/src/talker.py", "tick", 45),
    _rec('a \\"b\\"', 20, "talker", 1700000003_000000000, "/ws/src/talker.py", "tick", 46),
    _rec("", 20, "talker", 1700000003_000000001, "/ws/src/talker.py", "tick", 47),
    _rec('x";"y', 20, "talker", 1700000003_000000002, "/ws/src/talker.py", "tick", 48),
    _rec("timer fired", 30, "cpp_node", 1700000004_000000000, "/ws/src/node.cpp", "void ns::Node::on_timer()", 7),
    _rec("ends with a newline\n", 20, "talker", 1700000005_000000000, "/ws/src/talker.py", "tick", 49),
    _rec("tab\there", 20, "talker", 0, "", "", 0),
]


def test_reads_rqt_console_ros2_file_exactly():
    data = (DATA / "rqt_console_ros2.csv").read_bytes()
    records = read_cleanly(data, RqtCsvFormat(), "rqt_console_ros2.csv")
    assert [fields(r) for r in records] == [fields(r) for r in ROS2_EXPECTED]


def test_writes_the_bytes_rqt_console_writes():
    data = (DATA / "rqt_console_ros2.csv").read_bytes()
    assert _write(RqtCsvWriter(), ROS2_EXPECTED) == data


def test_reads_and_writes_rqt_console_ros1_variant():
    data = (DATA / "rqt_console_ros1.csv").read_bytes()
    records = read_cleanly(data, RqtCsvFormat(), "r1")
    assert [r.level for r in records] == [20, 30, 10, 40, 50]
    assert records[1].msg == 'say "hi";\nsecond line'
    assert records[3].msg == "error ✓"
    assert records[3].file == "/src/node.cpp"
    assert records[3].function == "void Node::cb(const std_msgs::String_<std::allocator<void> >::ConstPtr&)"
    assert records[3].line == 30
    assert [r.topics for r in records[:3]] == ["/chatter,/rosout", "/rosout", ""]
    # Written back as ROS 1: the same bytes, topics too.
    assert _write(RqtCsvWriter(ros1=True), records) == data


def test_ros1_csv_writes_levels_between_steps_as_the_step_below(tmp_path):
    records = [LogRecord(i, level, "n", f"m{level}", "", "", 0, "") for i, level in enumerate((5, 25, 35, 45, 55))]
    written = _write(RqtCsvWriter(ros1=True), records).decode().splitlines()
    assert written[0].split(";")[1] == "severity"
    assert [line.split(";")[1] for line in written[1:]] == ['"1"', '"2"', '"4"', '"8"', '"16"']
    path = tmp_path / "levels.csv"
    save_records(records, path, "rqt1")
    loaded, problems = read_text(path.read_bytes(), RqtCsvFormat(), "levels.csv")
    assert list(problems) == [] and [r.level for r in loaded] == [10, 20, 30, 40, 50]


@pytest.mark.parametrize("save_format", ["rqt", "rqt1", "jsonl"])
def test_round_trip_keeps_every_field(tmp_path, save_format):
    records = hostile_records(source="robot.bag")
    path = tmp_path / ("out.jsonl" if save_format == "jsonl" else "out.csv")
    assert save_records(records, path, save_format) == len(records)
    text_format = JsonLinesFormat() if save_format == "jsonl" else RqtCsvFormat()
    loaded = read_cleanly(path.read_bytes(), text_format, "out")
    if save_format == "jsonl":
        assert [fields(r) for r in loaded] == [fields(r) for r in records]
    else:  # rqt_console's format has no source column: records take the file's name
        assert [fields(r)[:7] for r in loaded] == [fields(r)[:7] for r in records]
        assert {r.source for r in loaded} == {"out"}


def test_jsonl_keeps_lone_surrogates_and_unknown_levels():
    record = LogRecord(5, 25, "n\udc80", "bad \ud800 text", "", "", 0, "")
    data = _write(JsonLinesWriter(), [record])
    data.decode("utf-8")  # always valid UTF-8
    loaded = read_cleanly(data, JsonLinesFormat(), "src")
    assert loaded[0].msg == "bad \ud800 text" and loaded[0].level == 25 and loaded[0].source == "src"


def test_split_location():
    assert split_location("/a/b.py:tick:42") == ("/a/b.py", "tick", 42)
    assert split_location("/a/n.cpp:void A::b():7") == ("/a/n.cpp", "void A::b()", 7)
    assert split_location("C:\\src\\n.cpp:main:3") == ("C:\\src\\n.cpp", "main", 3)
    assert split_location("::0") == ("", "", 0)
    assert split_location("no line here") == ("no line here", "", 0)


def test_rqt_bad_rows_are_reported_by_line_and_the_rest_loads():
    data = (
        b"message;severity;node;stamp;location\n"
        b"stray text\n"
        b'"ok";"20";"n";"1.000000000";"f:g:1"\n'
        b'"bad severity";"21";"n";"1.000000000";"f:g:1"\n'
        b'"bad stamp";"20";"n";"yesterday";"f:g:1"\n'
        b'"too few";"20"\n'
        b'"ok2";"30";"n";"2.000000000";"f:g:2"\n'
        b'"cut off in the mid'
    )
    records, problems = read_text(data, RqtCsvFormat(), "bad.csv")
    assert [r.msg for r in records] == ["ok", "ok2"]
    found = {(p.line, p.what.split(":")[0]) for p in problems}
    assert (2, "not a rqt_console CSV record") in found
    assert (4, "unknown severity 21 (expected 10, 20, 30, 40 or 50)") in found
    assert (5, "stamp is not sec.nsec") in found
    assert (6, "row has 2 fields, the header 5") in found
    assert (8, "row does not end with '\"' (truncated?)") in found
    assert (8, "the file ends in the middle of a line") in found


def test_rqt_without_header_says_so():
    records, problems = read_text(b'"a";"20";"n";"1.0";"f:g:1"\n', RqtCsvFormat(), "x.csv")
    assert records == []
    assert "no rqt_console header" in problems.items[0].what and problems.items[0].line == 1


def test_jsonl_bad_lines_are_reported():
    good = json.dumps({"stamp_ns": 1, "level": "warn", "node": "n", "msg": "m"})
    data = "\n".join([good, "{not json", '{"stamp_ns": "x", "msg": "m"}', "[1, 2]", "", good, '{"stamp']).encode()
    records, problems = read_text(data, JsonLinesFormat(), "x.jsonl")
    assert [r.level for r in records] == [30, 30]
    assert [p.line for p in problems] == [2, 3, 4, 7, 7]
    assert "'stamp_ns' is not an integer" in problems.items[1].what


def test_json_lines_keep_ros1_topics_and_leave_them_out_when_none():
    plain = LogRecord(1, 20, "n", "m", "", "", 0, "s")
    ros1 = LogRecord(2, 30, "n", "m", "", "", 0, "s", "/rosout,/chatter")
    written = _write(JsonLinesWriter(), [plain, ros1]).decode().splitlines()
    assert "topics" not in written[0] and '"topics": "/rosout,/chatter"' in written[1]
    records, problems = read_text(("\n".join(written) + "\n").encode(), JsonLinesFormat(), "x")
    assert list(problems) == [] and [r.topics for r in records] == ["", "/rosout,/chatter"]


def test_damaged_rqt_csv_keeps_the_row_before_each_bad_line():
    """Issue 11, item 5: a line that is no row used to take the valid row before it down
    with it, and the problem named that row's line."""
    data = (
        b"message;severity;node;stamp;location\n"
        b'"one";"20";"n";"1.000000000";"f:g:1"\n'
        b"GARBAGE\n"
        b'"two\nlines";"30";"n";"2.000000000";"f:g:2"\n'
        b"more garbage\n"
        b"and more\n"
        b'"three";"40";"n";"3.000000000";"f:g:3"\n'
    )
    records, problems = read_text(data, RqtCsvFormat(), "damaged.csv")
    assert [(r.msg, r.level) for r in records] == [("one", 20), ("two\nlines", 30), ("three", 40)]
    assert [(p.line, p.what) for p in problems] == [
        (3, "not a rqt_console CSV record: 'GARBAGE'"),
        (6, "not a rqt_console CSV record: 'more garbage' (and 1 more line up to line 7)"),
    ]


def test_rqt_rows_apart_with_blank_lines_and_crlf_endings():
    data = (
        b"message;severity;node;stamp;location\r\n"
        b'"one";"20";"n";"1.000000000";"f:g:1"\r\n'
        b"\r\n"
        b"\n"
        b'"two";"30";"n";"2.000000005";"f:g:2"\n'
        b"\n"
    )
    records = read_cleanly(data, RqtCsvFormat(), "blank.csv")
    assert [(r.msg, r.level, r.stamp_ns, r.line) for r in records] == [
        ("one", 20, 1_000_000_000, 1),
        ("two", 30, 2_000_000_005, 2),
    ]


def test_rqt_location_may_hold_the_field_separator_and_columns_may_be_missing():
    data = b'message;severity;node;stamp;location\n"m";"40";"n";"3.000000000";"odd";"name.py:f:9"\n'
    records, problems = read_text(data, RqtCsvFormat(), "odd.csv")
    assert list(problems) == [] and (records[0].msg, records[0].node) == ("m", "n")
    assert (records[0].file, records[0].function, records[0].line) == ('odd";"name.py', "f", 9)
    records, problems = read_text(b'message\n""\n', RqtCsvFormat(), "empty.csv")
    assert list(problems) == [] and [r.msg for r in records] == [""], "an empty message is a row"
    records, problems = read_text(b'message;severity\n"just this";"30"\n', RqtCsvFormat(), "two.csv")
    assert list(problems) == []
    assert [(r.msg, r.level, r.stamp_ns, r.node, r.file, r.line) for r in records] == [("just this", 30, 0, "", "", 0)]
    records, problems = read_text(b'message\n"only text"\n', RqtCsvFormat(), "one.csv")
    assert list(problems) == [] and [(r.msg, r.level) for r in records] == [("only text", 20)]


def test_rqt_bad_severities_name_the_value_and_the_expected_ones():
    data = (
        b"message;severity;node;stamp;topics;location\n"
        b'"a";"3";"n";"1.000000000";"";"f:g:1"\n'
        b'"b";"loud";"n";"1.000000000";"";"f:g:1"\n'
        b'"c";"16";"n";"1.000000000";"";"f:g:1"\n'
    )
    records, problems = read_text(data, RqtCsvFormat(), "r1.csv")
    assert [(r.msg, r.level) for r in records] == [("c", 50)]
    assert [(p.line, p.what) for p in problems] == [
        (2, "unknown ROS 1 severity 3 (expected 1, 2, 4, 8 or 16)"),
        (3, "severity is not a number: 'loud'"),
    ]


def test_damaged_ros1_csv_keeps_the_row_and_its_ros1_severity():
    data = b'message;severity;node;stamp;topics;location\n"warned";"4";"n";"1.000000000";"/rosout";"f:g:1"\nGARBAGE\n'
    records, problems = read_text(data, RqtCsvFormat(), "r1.csv")
    assert [(r.msg, r.level, r.source) for r in records] == [("warned", 30, "r1.csv")]
    assert [(p.line, p.what) for p in problems] == [(3, "not a rqt_console CSV record: 'GARBAGE'")]


def test_damaged_csv_tries_each_line_that_could_end_the_row():
    """The message's first line ends with a quote (escaped, so not the row's end): the row
    ends further down, and the stray line after it is reported on its own."""
    data = (
        b'message;severity;node;stamp;location\n"he said \\"hi\\"\nand left";"20";"n";"1.000000000";"f:g:1"\nGARBAGE\n'
    )
    records, problems = read_text(data, RqtCsvFormat(), "quote.csv")
    assert [r.msg for r in records] == ['he said "hi"\nand left']
    assert [(p.line, p.what) for p in problems] == [(4, "not a rqt_console CSV record: 'GARBAGE'")]


@pytest.mark.parametrize("junk, found", [(999, True), (1_000, False)])
def test_a_damaged_row_is_given_up_after_a_thousand_tries(junk, found):
    """Recovery is bounded: of the lines that could end a damaged row, the first 1,000 are
    tried; past them the group is one problem, and the row after it still loads."""
    lines = [b'"start', *[b'junk "'] * junk, b'tail";"20";"n";"1.000000000";"f:g:1"', b"GARBAGE"]
    data = b"message;severity;node;stamp;location\n" + b"\n".join(lines) + b"\n"
    data += b'"after";"30";"n";"2.000000000";"f:g:2"\n'
    records, problems = read_text(data, RqtCsvFormat(), "long.csv")
    if found:  # the 1,000th try ends the row
        assert [r.msg[-4:] for r in records] == ["tail", "fter"] and records[0].source == "long.csv"
        assert [p.line for p in problems] == [junk + 4]
    else:
        assert [r.msg for r in records] == ["after"], "the 1,001st is never tried"
        assert [p.line for p in problems] == [2]


def test_damaged_csv_with_windows_line_endings_keeps_its_rows():
    data = (
        b"message;severity;node;stamp;location\r\n"
        b'"one";"20";"n";"1.000000000";"f:g:1"\r\n'
        b"GARBAGE\r\n"
        b'"two";"30";"n";"2.000000000";"f:g:2"\r\n'
    )
    records, problems = read_text(data, RqtCsvFormat(), "crlf.csv")
    assert [r.msg for r in records] == ["one", "two"]
    assert [(p.line, p.what) for p in problems] == [(3, "not a rqt_console CSV record: 'GARBAGE\\r'")]


def test_rqt_writer_names_and_writes_in_chunks_with_unencodable_text_replaced():
    assert (RqtCsvWriter().name, RqtCsvWriter(ros1=True).name) == ("rqt", "rqt1")
    records = [LogRecord(i, 20, "n", f"m{i}", "f", "g", 1, "") for i in range(10_001)]
    records[5].msg = "lone \ud800 surrogate"
    records[-1].msg = "last \udc80 one"
    stream = io.BytesIO()
    counts = list(RqtCsvWriter().write(records, stream))
    assert counts == [10_000, 10_001]
    lines = stream.getvalue().decode("utf-8").splitlines()
    assert len(lines) == 10_002 and lines[0] == ";".join(("message", "severity", "node", "stamp", "location"))
    assert lines[6].startswith('"lone ? surrogate";"20"') and lines[-1].startswith('"last ? one";')


def test_rqt_header_forms():
    from console_tui.model.formats.rqt_csv import parse_header

    assert parse_header("message;severity;node;stamp;location\r") == (
        "message",
        "severity",
        "node",
        "stamp",
        "location",
    )
    assert parse_header("message;severity;message") is None, "a column twice"
    assert parse_header("message;colour") is None, "a column rqt_console has not"
    assert parse_header("severity;node") is None, "no message column"
    data = b"\n  \n" + b"message;severity\n" + b'"after blank lines";"40"\n'
    records, problems = read_text(data, RqtCsvFormat(), "blank-first.csv")
    assert list(problems) == [] and [r.msg for r in records] == ["after blank lines"]
    long_line = "x" * 100
    records, problems = read_text(long_line.encode() + b"\n", RqtCsvFormat(), "nohead.csv")
    assert problems.items[0].what == (
        "no rqt_console header (expected 'message;severity;node;stamp;location'), found " + repr("x" * 60)
    )


def test_split_location_without_a_function():
    assert split_location("file.py:12") == ("file.py", "", 12)
    assert split_location("C:\\src\\n.cpp:3") == ("C:\\src\\n.cpp", "", 3)
