"""Fuzzing the readers (issue 17): random bytes and mutated real inputs for every text
format, format detection, and the ROS 2 (CDR) and ROS 1 Log decoders. No exception may
escape a reader: bad input becomes problems (or the decoders' own error), never a crash.

The run is bounded for CI: a fixed number of examples, derandomized so a failure repeats.
``CONSOLE_TUI_FUZZ_EXAMPLES=5000`` runs more, with fresh random inputs each time.
"""

from __future__ import annotations

import io
import json
import os
import re
from datetime import timedelta

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from console_tui.model.formats import FormatError, Problems, TextFormat, detect_text_format, read_batches, text_formats
from console_tui.model.formats.jsonl import JsonLinesWriter
from console_tui.model.formats.ros1_log_msg import Ros1LogDecoder, Ros1LogError, encode_log
from console_tui.model.formats.ros2_log_msg import CdrError, LogDecoder, LogEncoder
from console_tui.model.formats.rqt_csv import RqtCsvWriter
from console_tui.model.store.record import LogRecord

from support.formats import DATA, hostile_records

_MORE = int(os.environ.get("CONSOLE_TUI_FUZZ_EXAMPLES", "0"))
FUZZ = settings(
    max_examples=_MORE or 60,
    deadline=timedelta(seconds=5),
    derandomize=not _MORE,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    database=None,
)
CUSTOM_TEMPLATE = "{time_as_nanoseconds} {severity} {name} {function_name} {file_name}:{line_number} | {message} | end"


def _written(writer, records: list[LogRecord]) -> bytes:
    stream = io.BytesIO()
    for _ in writer.write(records, stream):
        pass
    return stream.getvalue()


RUN = DATA / "ros_log" / "c0ffee00-d4b2-11eb-9c3e-0242ac110002"
#: One real input of each text format, to mutate.
SAMPLES: list[bytes] = [
    (DATA / "rqt_console_ros2.csv").read_bytes(),
    (DATA / "rqt_console_ros1.csv").read_bytes(),
    _written(RqtCsvWriter(), hostile_records()),
    _written(JsonLinesWriter(), hostile_records()),
    (RUN / "rosout.log").read_bytes(),
    b"0.000000000 INFO [/p/main.cpp:167(MapServer) [topics: /rosout] Kinetic line\n",
    b"[INFO] [1795345407.868935159] [ns.probe]: hello\n[WARN] [1795345407.869679808] [ns.probe]: multi\nline\n",
    b"1795345408542813893 INFO ns.probe tick /tmp/n.py:7 | multi\nline | end\n",
    (RUN / "roslaunch-robot-4242.log").read_bytes(),
    (RUN / "talker-2.log.1").read_bytes(),
    (RUN / "talker-2-stdout.log").read_bytes(),
    b"[ INFO] [1579418624.945503644, 0.500000000]: sim\n\x1b[33m[ WARN] [1579418625.0]: colour\x1b[0m\n",
    (DATA / "ros_log" / "2024-10-05-00-46-21-512000-robot-4242" / "launch.log").read_bytes(),
    b"[INFO] [launch]: start\n[talker-1] [INFO] [1671253879.374483100] [talker]: hi\n[gz-3] \n[talker-1] more\n",
]
#: What mutations put in: the characters these formats split on, and what breaks parsers.
TOKENS = [
    b"\n", b"\r\n", b'"', b'";"', b";", b"[", b"]", b"]: ", b"] [", b"{", b"}", b":", b",", b" ",
    b"\x00", b"\x1b[2J", b"\x1b]0;x\x07", b"\xff\xfe", b"\xe6\x97\xa5", b"\xed\xa0\x80",
    b"9" * 30, b"9" * 5000, b"-1", b".", b"[INFO]", b"[ERROR] ", b"[ INFO] ", b"[rosout][INFO] ",
    b"2021-13-45 25:61:61,999: ", b"1.000000000 INFO ", b"[topics: ", b"[talker-1] ", b"\\", b'\\"',
    b"[" * 3000, b"\t", "\u2028".encode(),
]  # fmt: skip


_WORD = re.compile(rb"[0-9A-Za-z_]+")
_NUMBER = re.compile(rb"[0-9]+")


@st.composite
def mutated(draw, samples: list[bytes]) -> bytes:
    """A sample with a few bytes flipped, words (a field: digits, a level, a name) replaced
    by tokens, tokens put in, parts cut out or repeated."""
    data = bytearray(draw(st.sampled_from(samples)))
    for _ in range(draw(st.integers(1, 8))):
        where = draw(st.integers(0, len(data)))
        kind = draw(st.sampled_from(["flip", "word", "number", "number", "insert", "delete", "repeat", "truncate"]))
        words = list((_NUMBER if kind == "number" else _WORD).finditer(data)) if kind in ("word", "number") else []
        if words:
            word = draw(st.sampled_from(words))
            if kind == "number":  # numbers too long for a machine word, or for Python's int()
                replacement = b"9" * draw(st.sampled_from([0, 1, 10, 19, 20, 21, 40, 4301, 6000]))
                replacement = draw(st.sampled_from([b"", b"-", b"+"])) + replacement
            else:
                replacement = draw(st.sampled_from(TOKENS))
            data[word.start() : word.end()] = replacement
        elif kind == "flip" and data:
            data[min(where, len(data) - 1)] = draw(st.integers(0, 255))
        elif kind == "insert":
            data[where:where] = draw(st.sampled_from(TOKENS))
        elif kind == "delete":
            del data[where : where + draw(st.integers(1, 40))]
        elif kind == "repeat":
            data[where:where] = data[where : where + draw(st.integers(1, 200))] * draw(st.integers(1, 3))
        else:
            del data[where:]
    return bytes(data)


INPUTS = st.one_of(
    st.binary(max_size=3000),
    mutated(SAMPLES),
    st.lists(st.sampled_from(TOKENS), max_size=40).map(b"".join),
)
#: Per sample: fewer examples each, but every format's fields get hit.
PER_SAMPLE = settings(FUZZ, max_examples=_MORE or 40)


def _formats() -> list[TextFormat]:
    return [fmt.for_file(name) for fmt in text_formats(extra_templates=(CUSTOM_TEMPLATE,)) for name in ("x.log",)] + [
        fmt.for_file("ns1-cam-7-stdout.log", 1_700_000_000_000_000_000) for fmt in text_formats()[-3:]
    ]


def _read_all(data: bytes, text_format: TextFormat) -> None:
    problems = Problems("fuzz")
    for batch in read_batches(io.BytesIO(data), text_format, "fuzz", problems, batch_size=7):
        for record in batch:
            assert isinstance(record, LogRecord)
            assert isinstance(record.stamp_ns, int) and isinstance(record.level, int)
            assert all(isinstance(text, str) for text in (record.node, record.msg, record.file, record.function))
    assert all(isinstance(problem.what, str) for problem in problems)
    assert all(isinstance(note, str) for note in text_format.notes())


@FUZZ
@given(INPUTS)
def test_no_input_escapes_a_text_reader(data):
    for text_format in _formats():
        _read_all(data, text_format)


@pytest.mark.parametrize("sample", range(len(SAMPLES)))
def test_mutations_of_each_format_are_read_by_it(sample):
    text_format = detect_text_format(SAMPLES[sample], text_formats(extra_templates=(CUSTOM_TEMPLATE,)), "s.log")

    @PER_SAMPLE
    @given(mutated([SAMPLES[sample]]))
    def read(data: bytes) -> None:
        _read_all(data, text_format.for_file("ns1-cam-7-stdout.log", 1))

    read()


@FUZZ
@given(INPUTS)
def test_detection_says_a_format_or_why_not(data):
    try:
        found = detect_text_format(data, text_formats(), "fuzz.log")
    except FormatError as error:
        assert str(error).startswith("fuzz.log: ")
        return
    _read_all(data, found.for_file("fuzz.log"))


def _ros2_messages() -> list[bytes]:
    encoder = LogEncoder()
    return [encoder.encode(record) for record in hostile_records()]


def _ros1_messages() -> list[bytes]:
    return [
        encode_log(stamp_ns=r.stamp_ns, level=1 << (r.level // 10 - 1), name=r.node, msg=r.msg, topics=["/rosout"])
        for r in hostile_records()
    ]


@FUZZ
@given(st.one_of(st.binary(max_size=400), mutated(_ros2_messages())))
def test_the_cdr_decoder_reads_or_refuses(data):
    try:
        record = LogDecoder().decode(data, "fuzz")
    except CdrError:
        return
    assert isinstance(record.msg, str) and isinstance(record.node, str)


@FUZZ
@given(st.one_of(st.binary(max_size=400), mutated(_ros1_messages())))
def test_the_ros1_decoder_reads_or_refuses(data):
    try:
        record = Ros1LogDecoder().decode(data, "fuzz")
    except Ros1LogError:
        return
    assert isinstance(record.msg, str) and isinstance(record.topics, str)


def test_the_fuzz_samples_read_cleanly_before_they_are_mutated():
    """Mutations start from good inputs: each sample is read by some format without a problem."""
    for sample in SAMPLES:
        found = detect_text_format(sample, text_formats(extra_templates=(CUSTOM_TEMPLATE,)), "sample.log")
        problems = Problems("s")
        records = [
            r for batch in read_batches(io.BytesIO(sample), found.for_file("x.log"), "s", problems) for r in batch
        ]
        assert records and not problems.items, (found.name, [str(p) for p in problems])


def test_json_nested_deep_is_a_problem_not_a_crash():
    from console_tui.model.formats import JsonLinesFormat

    problems = Problems("deep")
    data = (json.dumps({"stamp_ns": 1, "msg": "ok"}) + "\n" + "[" * 100_000 + "\n").encode()
    records = [r for batch in read_batches(io.BytesIO(data), JsonLinesFormat(), "deep", problems) for r in batch]
    assert [r.msg for r in records] == ["ok"] and [p.line for p in problems] == [2]
