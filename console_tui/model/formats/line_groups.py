"""Reading text log files: lines from blocks of bytes, and lines grouped into records.

Every text format here is read the same way: ``TextLines`` turns a binary stream into
numbered lines (split on ``\\n`` only, decoded as UTF-8, bad bytes replaced and
reported), and ``group_lines`` gathers the lines of one record, because a message
with newlines in it spans several lines in every one of these formats; ``group_records``
turns the groups into records, reporting the lines that make none.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from enum import Enum
from typing import BinaryIO

from ..inert_text import plural
from ..store.record import LogRecord
from .problems import Problems, RecordError

BLOCK_SIZE = 1 << 20
#: Longest line kept: the rest of a longer line is left out (and reported), so one line
#: costs at most this much memory however long it is in the file.
MAX_LINE = 16 << 20
#: Most lines one record may span before it is cut off (and reported).
MAX_RECORD_LINES = 100_000
#: Most characters one record may hold before it is cut off (and reported).
MAX_RECORD_CHARS = MAX_LINE


class TextLines:
    """The lines of a binary stream as ``(line_number, text)``, numbered from 1.

    ``offset`` is how many bytes have been turned into lines so far (for progress and
    for locating problems). Invalid UTF-8 is replaced with U+FFFD and NUL bytes are
    reported as binary data, each once per file, with line and byte offset. A line
    longer than ``MAX_LINE`` bytes keeps its first ``MAX_LINE`` bytes; the rest of it is
    read past (not kept) and reported.
    """

    def __init__(self, stream: BinaryIO, problems: Problems, *, block_size: int = BLOCK_SIZE) -> None:
        self.stream = stream
        self.problems = problems
        self.block_size = block_size
        self.offset = 0
        #: Lines produced so far (the last line's number).
        self.lines_read = 0
        #: False when the stream's last line had no ``\n`` (often: a truncated file).
        self.ended_with_newline = True
        self._reported_decode = False
        self._reported_nul = False

    def __iter__(self) -> Iterator[tuple[int, str]]:
        line_number = 1
        pending = b""
        left_out = -1  # >= 0 while reading past the rest of an over-long line
        while True:
            block = self.stream.read(self.block_size)
            if not block:
                break
            if left_out >= 0:
                end = block.find(b"\n")
                if end < 0:
                    left_out += len(block)
                    self.offset += len(block)
                    continue
                left_out += end
                self.offset += end + 1
                self._report_cut(line_number, left_out)
                left_out = -1
                line_number += 1
                block = block[end + 1 :]
                if not block:
                    continue
            data = pending + block if pending else block
            cut = data.rfind(b"\n")
            if cut < 0:
                pending = data
                if len(pending) > MAX_LINE:
                    kept = _char_boundary(pending, MAX_LINE)
                    yield line_number, self._decode(pending[:kept], line_number)
                    left_out = len(pending) - kept
                    self.offset += len(pending)
                    pending = b""
                continue
            complete, pending = data[: cut + 1], data[cut + 1 :]
            lines = self._decode(complete, line_number).split("\n")
            lines.pop()  # the empty text after the final newline
            for text in lines:
                yield line_number, text
                line_number += 1
            self.offset += len(complete)
        if left_out >= 0:
            self.ended_with_newline = False
            self._report_cut(line_number, left_out)
            line_number += 1
        elif pending:
            self.ended_with_newline = False
            yield line_number, self._decode(pending, line_number)
            self.offset += len(pending)
            line_number += 1
        self.lines_read = line_number - 1

    def _report_cut(self, line_number: int, left_out: int) -> None:
        self.problems.add(
            f"line longer than {MAX_LINE >> 20} MiB: its first {MAX_LINE >> 20} MiB were kept, "
            f"the {left_out:,} bytes after them left out",
            line=line_number,
        )

    def _decode(self, data: bytes, first_line: int) -> str:
        if not self._reported_nul:
            nul = data.find(b"\x00")
            if nul >= 0:
                self._reported_nul = True
                self.problems.add(
                    "binary data (NUL bytes) in a text file",
                    line=first_line + data.count(b"\n", 0, nul),
                    offset=self.offset + nul,
                )
        try:
            return data.decode("utf-8")
        except UnicodeDecodeError as error:
            if not self._reported_decode:
                self._reported_decode = True
                self.problems.add(
                    f"bytes that are not UTF-8 (byte {self.offset + error.start}): shown as \ufffd",
                    line=first_line + data.count(b"\n", 0, error.start),
                )
            return data.decode("utf-8", errors="replace")


def _char_boundary(data: bytes, limit: int) -> int:
    """The largest cut at or below ``limit`` that does not split a UTF-8 character."""
    cut = limit
    while cut > limit - 4 and cut > 0 and data[cut] & 0xC0 == 0x80:
        cut -= 1
    return cut if cut > limit - 4 else limit


class LineKind(Enum):
    """How a record-grouping rule sees one line."""

    START = 1  # the first line of a record
    MORE = 2  # continues the record before it (or is stray text before any record)
    SKIP = 3  # belongs to no record (a file's banner, for example)


@dataclass(slots=True)
class LineGroup:
    """Lines that belong together: one record, or stray lines before the first record."""

    line: int
    lines: list[str]
    is_record: bool

    @property
    def text(self) -> str:
        return "\n".join(self.lines)


def group_lines(
    lines: Iterable[tuple[int, str]],
    classify: Callable[[str], LineKind],
    problems: Problems,
) -> Iterator[LineGroup]:
    """Group numbered lines into records: a START line and the MORE lines after it.

    MORE lines before the first START come out as one group with ``is_record=False``
    (blank ones are dropped), so the format can say what it found there. A record is cut
    (and the cut reported) after ``MAX_RECORD_LINES`` lines or ``MAX_RECORD_CHARS``
    characters; the lines after the cut come out as a group that is no record.
    """
    group: LineGroup | None = None
    chars = 0
    for number, text in lines:
        kind = classify(text)
        if kind is LineKind.START:
            if group is not None:
                yield group
            group = LineGroup(number, [text], True)
            chars = len(text)
        elif kind is LineKind.SKIP:
            if group is not None and group.is_record:
                continue
            if group is not None:
                yield group
                group = None
        elif group is None:
            if text.strip():
                group = LineGroup(number, [text], False)
                chars = len(text)
        elif len(group.lines) >= MAX_RECORD_LINES or chars + len(text) > MAX_RECORD_CHARS:
            if group.is_record:
                problems.add(
                    f"record of more than {MAX_RECORD_LINES:,} lines or {MAX_RECORD_CHARS:,} characters: cut",
                    line=group.line,
                )
            yield group
            group = LineGroup(number, [text], False)
            chars = len(text)
        else:
            group.lines.append(text)
            chars += len(text) + 1
    if group is not None:
        yield group


def stray_text_problem(group: LineGroup, problems: Problems, format_name: str) -> None:
    """Report lines that belong to no record of ``format_name``."""
    count = len(group.lines)
    first = group.lines[0]
    shown = first if len(first) <= 60 else first[:57] + "..."
    what = f"not a {format_name} record: {shown!r}"
    if count > 1:
        what += f" (and {plural(count - 1, 'more line')} up to line {group.line + count - 1})"
    problems.add(what, line=group.line)


def group_records(
    groups: Iterable[LineGroup],
    parse: Callable[[LineGroup], LogRecord],
    problems: Problems,
    format_name: str,
) -> Iterator[LogRecord]:
    """The record ``parse`` makes of each group that is one; stray lines, and groups
    ``parse`` refuses with a ``RecordError``, are reported instead."""
    for group in groups:
        if not group.is_record:
            stray_text_problem(group, problems, format_name)
            continue
        try:
            yield parse(group)
        except RecordError as error:
            problems.add(str(error), line=group.line)
