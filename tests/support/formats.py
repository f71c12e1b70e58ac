"""Small helpers for the file-format tests."""

from __future__ import annotations

import io
import random
from pathlib import Path

from console_tui.model.formats import Problems, TextFormat, read_batches
from console_tui.model.store.record import LogRecord

DATA = Path(__file__).parent.parent / "data"

#: Messages that break naive writers and readers.
HOSTILE_MESSAGES = [
    "plain",
    "",
    'say "hi"',
    "semi;colons;everywhere",
    '";"',
    '"";""',
    'x";"y',
    "ends with backslash \\",
    'backslash quote \\" inside',
    '\\\\""\\',
    "line one\nline two",
    "\nstarts with a newline",
    "ends with a newline\n",
    "blank\n\nline",
    "\r\nwindows\r\n",
    "tab\tand\vvertical\fform",
    "naïve café ✓ 日本語 🚀",
    "\u2028line separator\u2029paragraph",
    "{not json} [INFO] [1.000000000] [x]: fake header",
    '"starts with a quote',
    '";"20";"fake";"1.000000000";"::0"',
    "1700000000.000000000 INFO /fake [f.py:1(f)] looks like rosout",
    "\x1b[31mcolour\x1b[0m",
]


def hostile_records(source: str = "") -> list[LogRecord]:
    records = []
    for index, message in enumerate(HOSTILE_MESSAGES):
        records.append(
            LogRecord(
                stamp_ns=1_700_000_000_000_000_000 + index * 1_000_000_007,
                level=(10, 20, 30, 40, 50)[index % 5],
                node=("talker", "ns.talker", "ns.talker.child")[index % 3],
                msg=message,
                file=("/ws/src/talker.py", "/ws/src/node.cpp", "")[index % 3],
                function=("tick", "void ns::Node::on_timer()", "")[index % 3],
                line=(42, 7, 0)[index % 3],
                source=source,
            )
        )
    return records


def read_text(data: bytes, text_format: TextFormat, source: str = "test") -> tuple[list[LogRecord], Problems]:
    problems = Problems(source)
    records = [r for batch in read_batches(io.BytesIO(data), text_format, source, problems) for r in batch]
    return records, problems


def read_cleanly(data: bytes, text_format: TextFormat, source: str = "test") -> list[LogRecord]:
    """The records ``data`` reads as; it must read without a problem."""
    records, problems = read_text(data, text_format, source)
    assert list(problems) == []
    return records


def fields(record: LogRecord) -> tuple:
    """Every field but seq."""
    return (
        record.stamp_ns,
        record.level,
        record.node,
        record.msg,
        record.file,
        record.function,
        record.line,
        record.source,
    )


#: What a ROS 1 string's length prefix and UTF-8 meet in the wild: quotes, backslashes, tabs,
#: newlines, accents, CJK, emoji.
ROS1_ALPHABET = "abcXYZ_./:0 é日本語🤖\t\"';\\\n"


def random_text(rng: random.Random, longest: int) -> str:
    return "".join(rng.choice(ROS1_ALPHABET) for _ in range(rng.randint(0, longest)))


def random_ros1_log(rng: random.Random) -> dict:
    """The fields of a random ``rosgraph_msgs/Log``, as ``encode_log`` takes them."""
    return {
        "stamp_ns": rng.randint(0, 2**32 - 1) * 1_000_000_000 + rng.randint(0, 999_999_999),
        "level": rng.choice([1, 2, 4, 8, 16]),
        "name": random_text(rng, 20),
        "msg": random_text(rng, 300),
        "file": random_text(rng, 30),
        "function": random_text(rng, 30),
        "line": rng.randint(0, 2**32 - 1),
        "topics": [random_text(rng, 10) for _ in range(rng.randint(0, 3))],
        "seq": rng.randint(0, 2**32 - 1),
        "frame_id": random_text(rng, 5),
    }
