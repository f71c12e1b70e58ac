"""The direct CDR decoder for rcl_interfaces/msg/Log, field for field against rclpy, and on hostile input."""

from __future__ import annotations

import random
import struct

import pytest

from console_tui.model.formats.ros2_log_msg import CdrError, LogDecoder
from console_tui.model.store.record import LogRecord

FIELDS = ("stamp_ns", "level", "node", "msg", "file", "function", "line", "source")
ALPHABET = "abcXYZ_./:0 é日本語🤖\t\"';\\"


def cdr_string(text: bytes, pos: int, big: bool, *, length: int | None = None, nul: bool = True) -> bytes:
    """A CDR string at payload offset ``pos``: padding, length (NUL included), bytes, NUL."""
    body = text + b"\x00" if nul else text
    stated = len(body) if length is None else length
    return b"\x00" * (-pos % 4) + struct.pack(">I" if big else "<I", stated) + body


def encode_log(
    *,
    sec: int = 1,
    nanosec: int = 2,
    level: int = 20,
    strings: tuple[bytes, bytes, bytes, bytes] = (b"node", b"hello", b"file.py", b"fn"),
    line: int = 7,
    big: bool = False,
    kind: int | None = None,
    lengths: tuple[int | None, ...] = (None, None, None, None),
    nul: bool = True,
) -> bytes:
    """A Log message serialized by hand (so byte order, kind and lengths can be chosen)."""
    order = ">" if big else "<"
    header = bytes([0, kind if kind is not None else (0 if big else 1), 0, 0])
    payload = struct.pack(order + "iIB", sec, nanosec, level)
    for text, length in zip(strings, lengths, strict=False):
        payload += cdr_string(text, len(payload), big, length=length, nul=nul)
    payload += b"\x00" * (-len(payload) % 4) + struct.pack(order + "I", line)
    return header + payload


def fields(record: LogRecord) -> tuple:
    return tuple(getattr(record, name) for name in FIELDS)


# -- against rclpy's own serialization ---------------------------------------------------------


@pytest.fixture(scope="module")
def rclpy_log():
    pytest.importorskip("rclpy")
    from rcl_interfaces.msg import Log
    from rclpy.serialization import deserialize_message, serialize_message

    from console_tui.sources.ros2.log_message import log_to_record

    def make(sec, nanosec, level, name, msg, file, function, line):
        message = Log()
        message.stamp.sec, message.stamp.nanosec = sec, nanosec
        message.level, message.line = level, line
        message.name, message.msg, message.file, message.function = name, msg, file, function
        return message

    def rclpy_record(data: bytes) -> LogRecord:
        return log_to_record(deserialize_message(data, Log), "/rosout")

    return make, serialize_message, rclpy_record


def random_text(rng: random.Random, longest: int) -> str:
    return "".join(rng.choice(ALPHABET) for _ in range(rng.randint(0, longest)))


def test_matches_rclpy_for_many_random_messages(rclpy_log):
    make, serialize, rclpy_record = rclpy_log
    rng = random.Random(20240611)
    decoder = LogDecoder()
    for _ in range(3000):
        values = (
            rng.choice([0, 1, -1, 2**31 - 1, -(2**31), rng.randint(-(2**31), 2**31 - 1)]),
            rng.choice([0, 999_999_999, 2**32 - 1, rng.randint(0, 2**32 - 1)]),
            rng.choice([10, 20, 30, 40, 50, 0, 255, rng.randint(0, 255)]),
            random_text(rng, 9),  # short names: every length mod 4, so every padding
            random_text(rng, 200),
            random_text(rng, 13),
            random_text(rng, 7),
            rng.choice([0, 1, 2**32 - 1, rng.randint(0, 2**32 - 1)]),
        )
        data = serialize(make(*values))
        record = decoder.decode(data, "/rosout")
        assert fields(record) == fields(rclpy_record(data))
        sec, nanosec, level, name, msg, file, function, line = values
        assert fields(record) == (sec * 1_000_000_000 + nanosec, level, name, msg, file, function, line, "/rosout")


def test_every_string_length_and_padding_matches_rclpy(rclpy_log):
    make, serialize, rclpy_record = rclpy_log
    decoder = LogDecoder()
    for a in range(9):
        for b in range(9):
            for c in range(5):
                for d in range(5):
                    data = serialize(make(3, 4, 30, "n" * a, "é" * b, "f" * c, "g" * d, 99))
                    assert fields(decoder.decode(data, "/rosout")) == fields(rclpy_record(data))


def test_invalid_utf8_missing_and_embedded_nul_read_as_rclpy_reads_them(rclpy_log):
    _make, _serialize, rclpy_record = rclpy_log
    decoder = LogDecoder()
    cases = [
        (b"\xff\xfe", b"h\xc3\x28llo", b"\xed\xa0\x80", b"\xc3"),  # bad UTF-8, lone surrogate, cut sequence
        (b"a\x00b", b"msg\x00tail", b"", b"\x00"),  # embedded NULs end the string
    ]
    for strings in cases:
        data = encode_log(strings=strings)
        record = decoder.decode(data, "/rosout")
        assert fields(record) == fields(rclpy_record(data))
    assert "\ufffd" in decoder.decode(encode_log(strings=cases[0])).node
    # No terminating NUL: the stated bytes are the text (rclpy does the same).
    data = encode_log(strings=(b"abcd", b"x", b"yz", b"fn\xc3"), nul=False)
    assert fields(decoder.decode(data, "/rosout")) == fields(rclpy_record(data))
    assert decoder.decode(data).node == "abcd"
    # Length 0 (some writers send it for empty strings): empty, as rclpy reads it.
    data = encode_log(strings=(b"", b"", b"", b""), nul=False)
    assert fields(decoder.decode(data, "/rosout")) == fields(rclpy_record(data))
    assert decoder.decode(data).msg == ""


# -- byte orders and encapsulations -----------------------------------------------------------------


@pytest.mark.parametrize("big", [False, True])
@pytest.mark.parametrize("xcdr2", [False, True])
def test_both_byte_orders_and_plain_xcdr2(big, xcdr2):
    kind = (6 if big else 7) if xcdr2 else None
    strings = (b"ns.talker", "héllo wörld".encode(), b"/src/a.cpp", b"spin")
    data = encode_log(sec=-5, nanosec=2**32 - 1, level=40, strings=strings, line=2**32 - 1, big=big, kind=kind)
    record = LogDecoder().decode(data, "/rosout_agg")
    assert fields(record) == (
        -5 * 1_000_000_000 + 2**32 - 1,
        40,
        "ns.talker",
        "héllo wörld",
        "/src/a.cpp",
        "spin",
        2**32 - 1,
        "/rosout_agg",
    )


def test_bytes_like_inputs():
    data = encode_log()
    decoder = LogDecoder()
    expected = fields(decoder.decode(data))
    assert fields(decoder.decode(bytearray(data))) == expected
    assert fields(decoder.decode(memoryview(data))) == expected


@pytest.mark.parametrize("header", [b"", b"\x00", b"\x00\x02", b"\x00\x08", b"\x00\x0a", b"\x01\x01", b"\xff\xff"])
def test_unknown_encapsulations_are_refused(header):
    data = header + encode_log()[len(header) :] if len(header) == 2 else header
    with pytest.raises(CdrError, match="encapsulation"):
        LogDecoder().decode(data)


# -- hostile input --------------------------------------------------------------------------------


def test_every_truncation_is_a_clear_error():
    data = encode_log(strings=(b"a.b", "mes日本".encode(), b"f", b""))
    decoder = LogDecoder()
    for cut in range(2, len(data)):
        with pytest.raises(CdrError):
            decoder.decode(data[:cut])
    decoder.decode(data)


@pytest.mark.parametrize("field", range(4))
@pytest.mark.parametrize("length", [2**32 - 1, 2**31, 1_000_000, 200])
def test_lengths_past_the_end_are_clear_errors(field, length):
    lengths = [None] * 4
    lengths[field] = length
    data = encode_log(lengths=tuple(lengths))
    with pytest.raises(CdrError, match=r"claims|truncated"):
        LogDecoder().decode(data)


def test_huge_strings_decode_in_full():
    big = "x" * 5_000_000 + "é"
    data = encode_log(strings=(b"n", big.encode(), b"f" * 100_000, b"g"))
    record = LogDecoder().decode(data)
    assert record.msg == big and record.file == "f" * 100_000 and record.line == 7


def test_random_garbage_and_mutations_never_raise_anything_but_cdr_error():
    rng = random.Random(7)
    decoder = LogDecoder()
    valid = encode_log(strings=(b"node.x", b"some message text", b"/a/b.py", b"fn"))
    inputs = [bytes(rng.getrandbits(8) for _ in range(rng.randint(0, 80))) for _ in range(2000)]
    inputs += [b"\x00\x01" + bytes(rng.getrandbits(8) for _ in range(rng.randint(0, 80))) for _ in range(2000)]
    for _ in range(3000):
        mutated = bytearray(valid)
        for _ in range(rng.randint(1, 4)):
            mutated[rng.randrange(2, len(mutated))] = rng.getrandbits(8)
        inputs.append(bytes(mutated))
    decoded = 0
    for data in inputs:
        try:
            record = decoder.decode(data)
        except CdrError:
            continue
        decoded += 1
        assert isinstance(record.msg, str) and isinstance(record.node, str)
    assert decoded > 0


# -- shared strings ----------------------------------------------------------------------------------


def test_repeated_names_are_shared_between_records():
    decoder = LogDecoder()
    first = decoder.decode(encode_log(strings=(b"robot.planner", b"one", b"/src/plan.cpp", b"plan")))
    second = decoder.decode(encode_log(strings=(b"robot.planner", b"two", b"/src/plan.cpp", b"plan")))
    assert first.node is second.node and first.file is second.file and first.function is second.function
    assert (first.msg, second.msg) == ("one", "two")


def test_the_string_caches_stay_bounded():
    decoder = LogDecoder(intern_limit=50, intern_max_bytes=32)
    for number in range(500):
        strings = (f"node{number}".encode(), b"m", b"x" * 40, f"fn{number}".encode())
        record = decoder.decode(encode_log(strings=strings, line=number))
        assert (record.node, record.file, record.function, record.line) == (
            f"node{number}",
            "x" * 40,
            f"fn{number}",
            number,
        )
        assert len(decoder._names) <= 50 and len(decoder._tails_le) <= 50
    assert b"x" * 40 + b"\x00" not in decoder._names


def test_a_cached_tail_is_read_per_byte_order():
    decoder = LogDecoder()
    little = decoder.decode(encode_log(strings=(b"n", b"m", b"f", b"g"), line=1))
    big = decoder.decode(encode_log(strings=(b"n", b"m", b"f", b"g"), line=1, big=True))
    assert (little.file, little.function, little.line) == (big.file, big.function, big.line) == ("f", "g", 1)


# -- what the errors say, and what a caller that takes refused messages gets -----------------------


@pytest.mark.parametrize(
    "field, lengths, expected",
    [
        ("name", (200, None, None, None), "Log message field 'name' claims 200 bytes, only 44 left"),
        ("msg", (None, 200, None, None), "Log message field 'msg' claims 200 bytes, only 32 left"),
        ("file", (None, None, 200, None), "Log message field 'file' claims 200 bytes, only 20 left"),
        ("function", (None, None, None, 200), "Log message field 'function' claims 200 bytes, only 8 left"),
    ],
)
def test_a_length_past_the_end_names_the_field_and_what_is_left(field, lengths, expected):
    with pytest.raises(CdrError) as error:
        LogDecoder().decode(encode_log(lengths=lengths))
    assert str(error.value) == expected


@pytest.mark.parametrize("field, start", [(0, 20), (1, 32), (2, 44), (3, 56)])
def test_a_string_up_to_the_last_byte_is_read_and_what_should_follow_is_missing(field, start):
    """A string may reach the very end of the bytes; what must follow it (the other
    strings, the line) is then missing: the message is truncated, not over-long."""
    size = len(encode_log())
    lengths = [None] * 4
    lengths[field] = size - start
    with pytest.raises(CdrError) as error:
        LogDecoder().decode(encode_log(lengths=tuple(lengths)))
    assert str(error.value) == f"Log message truncated: {size} bytes"


def test_unknown_encapsulation_and_truncation_messages():
    with pytest.raises(CdrError) as error:
        LogDecoder().decode(b"")
    assert str(error.value) == "not a CDR Log message: encapsulation missing"
    with pytest.raises(CdrError) as error:
        LogDecoder().decode(b"\x12\x34" + encode_log()[2:])
    assert str(error.value) == "not a CDR Log message: encapsulation 1234"
    with pytest.raises(CdrError) as error:
        LogDecoder().decode(encode_log()[:10])
    assert str(error.value) == "Log message truncated: 10 bytes"


def test_refused_messages_go_to_the_callback_whose_records_take_their_place():
    good = [encode_log(strings=(b"n", f"m{i}".encode(), b"f", b"g")) for i in range(3)]
    bad = [b"\x00\x01junk", encode_log()[:9]]
    seen: list[tuple[bytes, str]] = []

    def refused(data: bytes, error: CdrError) -> LogRecord | None:
        seen.append((data, str(error)))
        return LogRecord(0, 40, "stand-in", "in place of a bad one") if data == bad[0] else None

    records = LogDecoder().decode_many([good[0], bad[0], good[1], bad[1], good[2]], "/rosout", refused)
    assert [r.msg for r in records] == ["m0", "in place of a bad one", "m1", "m2"]
    assert [(r.level, r.node) for r in records][1] == (40, "stand-in")
    assert [data for data, _ in seen] == bad
    assert seen[1][1] == "Log message truncated: 9 bytes"
    assert [r.source for r in records if r.node == "n"] == ["/rosout"] * 3
    assert LogDecoder().decode_many([good[0]])[0].source == "", "no source unless given"
    assert LogDecoder().decode(good[0]).source == ""


def test_columns_hold_what_records_hold():
    messages = [encode_log(strings=(b"n", f"m{i}".encode(), b"f", b"g")) for i in range(3)]
    columns = LogDecoder().decode_columns(messages, "/rosout")
    assert columns.records() == LogDecoder().decode_many(messages, "/rosout")
    assert list(columns.msgs) == ["m0", "m1", "m2"] and list(columns.sources) == ["/rosout"] * 3
    assert len(LogDecoder().decode_columns([])) == 0


def test_a_message_with_several_nuls_ends_at_the_first():
    data = encode_log(strings=(b"node", b"first\x00second\x00third", b"file.py", b"fn"))
    assert LogDecoder().decode(data).msg == "first"
