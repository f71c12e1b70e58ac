"""Which format a file is in, from its first bytes (and, for recordings, its name)."""

from __future__ import annotations

from collections.abc import Sequence

from .line_format import TextFormat
from .line_groups import BLOCK_SIZE
from .problems import FormatError

#: Recordings, by the magic bytes they start with.
RECORDING_MAGIC: dict[bytes, str] = {
    b"#ROSBAG V2.0\n": "ros1-bag",
    b"\x89MCAP0\r\n": "mcap",
    b"SQLite format 3\x00": "sqlite3",
}
RECORDING_TITLES = {
    "ros1-bag": "ROS 1 bag",
    "mcap": "rosbag2 MCAP",
    "sqlite3": "rosbag2 sqlite3",
    "rosbag2": "rosbag2 recording",
}
#: How many bytes of a file detection looks at.
HEAD_SIZE = 64 * 1024
_DETECT_LINES = 50


def recording_kind(head: bytes) -> str | None:
    """``ros1-bag``, ``mcap`` or ``sqlite3`` when ``head`` starts like one, else None."""
    for magic, kind in RECORDING_MAGIC.items():
        if head.startswith(magic):
            return kind
    return None


def detect_text_format(
    head: bytes, candidates: Sequence[TextFormat], name: str, *, fallback: TextFormat | None = None
) -> TextFormat:
    """The format of a file that starts with ``head``: the first of ``candidates`` that
    recognises a line, trying its first non-blank lines in order (a file may start with
    lines of no record: a banner, output printed before the first log line, the end of a
    record cut by a rotation).

    ``fallback``, when given, is the answer for text no candidate recognises (captured
    output, known by the file's name). Otherwise raises ``FormatError`` saying why none
    fits: empty, binary, an old bag, or text in no known format (quoting its first line).
    """
    if not head:
        raise FormatError(f"{name}: the file is empty")
    if head.startswith(b"#ROSBAG V1"):
        raise FormatError(f"{name}: a ROS 1 bag of the old version 1.x format: 'rosbag fix' it first")
    if b"\x00" in head[:4096] or _mostly_binary(head[:4096]):
        shown = head[:8].hex(" ")
        raise FormatError(f"{name}: binary data, not a log file or a recording this tool reads (first bytes: {shown})")
    text = head[:BLOCK_SIZE].decode("utf-8", errors="replace")
    lines = text.split("\n")
    if len(head) >= HEAD_SIZE and len(lines) > 1:
        lines.pop()  # probably cut by the head's end
    tried = [line for line in lines if line.strip()][:_DETECT_LINES]
    if not tried:
        raise FormatError(f"{name}: no log records (only blank lines)")
    for line in tried:
        for candidate in candidates:
            if candidate.looks_like(line):
                return candidate
    if fallback is not None:
        return fallback
    first = tried[0]
    shown = first if len(first) <= 80 else first[:77] + "..."
    known = "; ".join(candidate.title for candidate in candidates)
    raise FormatError(
        f"{name}: not a log file this tool knows. Its first line is {shown!r}; known formats: {known}. "
        "For ROS 2 log files written with RCUTILS_CONSOLE_OUTPUT_FORMAT, pass --log-format."
    )


def _mostly_binary(sample: bytes) -> bool:
    if not sample:
        return False
    control = sum(1 for byte in sample if byte < 9 or 13 < byte < 32)
    return control * 10 > len(sample)
