"""The direct CDR decoder for rcl_interfaces/msg/Log, field for field against rclpy, and on hostile input."""

from __future__ import annotations

import random
import struct

import pytest

from console_tui.model.formats.ros2_log_msg import CdrError, LogDecoder
from console_tui.model.record import LogRecord

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

    from console_tui.sources.log_message import log_to_record

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
