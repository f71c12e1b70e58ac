"""Reading a big text log by its index: 4,096 records at a time, their columns and bytes, not their messages.

A night's ``rosout.log`` or a week of a node's log holds tens of millions of records: read
whole, their messages would fill memory (and the disk's cache of them, the disk). A file in
a format whose records can be read again from any record's first line
(``TextFormat.indexable``: ROS 2 node logs, rosout.log, rqt_console CSV, JSON Lines) is
read into ``IndexedChunk``s instead: each the columns of 4,096 records (what rules, jumps,
the timeline and the node panel read) and the byte range of their lines, from which the
store has their messages read again when they are read (``indexed_texts.py``).

ROS 2 node logs in rcutils' default format are read by the scanner in C (``rcutils_scan.c``,
about 1 GB/s); a chunk with a line it does not read exactly as the Python reader does, and
every other format, is read by the format's own reader, which says which line each record
begins on (``numbered_records``; its byte offset is counted from the lines read). A file
that grows while it is read is read to its new end; one that gets shorter is said
(``problems``) and read no further.
"""

from __future__ import annotations

import os
import threading
from array import array
from collections import deque
from collections.abc import Callable, Iterator
from typing import BinaryIO

from ...model.formats import TextLines
from ...model.formats.rcutils_log import RcutilsLogFormat
from ...model.store.chunk import CHUNK_SIZE, UINT32_MAX
from ...model.store.indexed_chunk import IdColumn, IndexedChunk
from ...model.store.record import LogRecord
from .compiled_scan import Scanner
from .indexed_texts import IndexedTexts, clamped
from .log_file import LogFile, TextLogFile

#: Bytes read at a time.
BLOCK = 8 << 20
#: Text logs at least this big are read by index; smaller ones are read whole (as cheap, and
#: a file edited later still shows what it held).
INDEX_FROM_BYTES = 16 << 20
#: The most bytes before a file's first record kept for reading its chunks again (a header).
HEADER_LIMIT = 1 << 20


def indexable(file: LogFile, *, from_bytes: int = INDEX_FROM_BYTES) -> bool:
    """Whether ``file`` is read by index: one text file (no rotated parts, no robot named
    for it) in an indexable format, of at least ``from_bytes``."""
    return (
        isinstance(file, TextLogFile)
        and len(file.parts) == 1
        and file.format.indexable
        and not file.robot
        and file.total >= from_bytes
    )


class FileIndexer:
    """Reads ``file`` into ``IndexedChunk``s handed to ``deliver`` (in the calling thread)."""

    def __init__(
        self,
        file: TextLogFile,
        deliver: Callable[[IndexedChunk], None],
        cancel: threading.Event,
        *,
        scanner: Scanner | None = None,
    ) -> None:
        self.file = file
        self.deliver = deliver
        self.cancel = cancel
        text_format = file.format
        default = isinstance(text_format, RcutilsLogFormat) and text_format.default_template
        #: The scanner in C (its ``contains`` serves every format), and its ``scan`` for the
        #: format it reads (else None: the format's reader reads all).
        self.scanner = scanner
        self.scan = scanner.scan if scanner is not None and default else None
        self.texts: IndexedTexts | None = None
        self.records = 0
        self._names: dict[str, tuple[dict[str, int], list[str]]] = {}
        self._c_nodes: dict[bytes, int] = {}
        self._c_names: list[bytes] = []
        self._nodes: list[str] = []  # the scanner's node names, decoded
        self._reported = (False, False)  # NUL bytes, bytes that are not UTF-8: said already

    def run(self) -> int:
        """Read the file to its end (and on, while it grows); the records read."""
        file = self.file
        with open(file.path, "rb") as stream:
            fd = stream.fileno()
            header = self._header(stream)
            self.texts = IndexedTexts(file.path, file.format, file.source, scanner=self.scanner, header=header)
            if self.scan is None:
                end, _line = self._read_in_python(stream, 0, 1, until_end=True)
                size = os.fstat(fd).st_size
                if size < end:
                    self._shortened(size, end)
            else:
                self._read_in_c(stream, fd)
        file.records = self.records
        if not self.cancel.is_set():
            file.done = file.total
        return self.records

    def _header(self, stream: BinaryIO) -> bytes:
        """The bytes before the first record, for a format that needs them again (CSV's header line)."""
        if not self.file.format.needs_header:
            return b""
        return stream.read(HEADER_LIMIT).split(b"\n", 1)[0] + b"\n"

    # -- at C speed ---------------------------------------------------------------------------------

    def _read_in_c(self, stream: BinaryIO, fd: int) -> None:
        assert self.scan is not None
        at, line = 0, 1  # where the scanner goes on (byte, line)
        start, start_line = 0, 1  # where the chunk being read begins
        stamps, levels, nodes = bytearray(), bytearray(), bytearray()
        data, block_at, size = b"", 0, 0  # the block read, from byte block_at of the file
        final = False  # the file's end reached: its last record ends there
        while not self.cancel.is_set():
            if at - block_at >= len(data) or at < block_at:
                size = os.fstat(fd).st_size
                if size < at:
                    self._shortened(size, at)
                    return
                data, block_at = os.pread(fd, min(BLOCK, size - at), at), at
                if not data:
                    break
            status, stop, _count, lines, new_stamps, new_levels, new_nodes, _, _ = self.scan(
                data, at - block_at, len(data), CHUNK_SIZE - len(levels), self._c_nodes, self._c_names, False, final
            )
            if self._c_names:
                self._nodes.extend(name.decode("utf-8") for name in self._c_names)
                self._c_names.clear()
            stamps += new_stamps
            levels += new_levels
            nodes += new_nodes
            moved = block_at + stop - at
            at, line = block_at + stop, line + lines
            self.file.done = at
            if len(levels) == CHUNK_SIZE:
                self._deliver_scanned(stamps, levels, nodes, start, at)
                stamps, levels, nodes = bytearray(), bytearray(), bytearray()
                start, start_line = at, line
                continue
            end_of_file = block_at + len(data) >= size
            if status == 2 and final:
                break  # (a last line without its newline, say: the format's reader says so)
            if status == 2 or (status == 1 and not end_of_file and moved == 0 and at == block_at):
                # A line the scanner does not read as the Python reader would (or a record
                # longer than a block): the format's reader reads this chunk.
                stamps, levels, nodes = bytearray(), bytearray(), bytearray()
                at, line = self._read_in_python(stream, start, start_line, until_end=False)
                start, start_line = at, line
                data = b""
                continue
            if status == 1:
                if not end_of_file:
                    data = b""  # the rest of the block is the start of a record: read on from it
                    continue
                if os.fstat(fd).st_size > size:
                    data, final = b"", False
                    continue  # it grew meanwhile: on to the new end
                if not final:
                    final = True  # once more: the last record ends at the end
                    continue
                if levels:
                    self._deliver_scanned(stamps, levels, nodes, start, at)
                return
        if self.cancel.is_set():
            return
        size = os.fstat(fd).st_size
        if size < at:
            self._shortened(size, at)
            return
        # The end: the last records (and a last line without its newline) read as the format says.
        self._read_in_python(stream, start, start_line, until_end=True)

    def _deliver_scanned(self, stamps: bytearray, levels: bytearray, nodes: bytearray, start: int, end: int) -> None:
        assert self.texts is not None
        count = len(levels)
        source = self.file.source
        node_ids = array("I")
        node_ids.frombytes(bytes(nodes))
        stamp_values = array("q")
        stamp_values.frombytes(bytes(stamps))
        none = IdColumn(None, [""])
        self._hand_over(
            IndexedChunk(
                stamp_values,
                array("B", levels),
                IdColumn(node_ids, self._nodes),
                none,
                none,
                IdColumn(None, [source]),
                None,
                start,
                end,
                self.texts,
                verbatim=True,  # the scanner reads only lines whose messages are their bytes
            ),
            count,
        )

    # -- with the format's own reader ---------------------------------------------------------------

    def _read_in_python(self, stream: BinaryIO, start: int, first_line: int, *, until_end: bool) -> tuple[int, int]:
        """Read records from byte ``start`` (line ``first_line``) with the format's reader, a
        chunk at a time (one chunk only unless ``until_end``); where reading stopped (the next
        record's offset and line)."""
        stream.seek(start)
        lines = _OffsetLines(stream, self.file, start, first_line)
        lines._reported_nul, lines._reported_decode = self._reported  # (once a file, as reading it whole says them)
        try:
            return self._read_lines(lines, start, first_line, until_end=until_end)
        finally:
            self._reported = lines._reported_nul, lines._reported_decode

    def _read_lines(self, lines: _OffsetLines, start: int, first_line: int, *, until_end: bool) -> tuple[int, int]:
        pending: list[LogRecord] = []
        chunk_start = start
        for number, record in self.file.format.numbered_records(lines, self.file.source, self.file.problems):
            if len(pending) == CHUNK_SIZE:
                offset = lines.offset_of(number)
                self._deliver_records(pending, chunk_start, offset)
                pending, chunk_start = [], offset
                if not until_end:
                    return offset, number
            if self.cancel.is_set():
                return chunk_start, number
            pending.append(record)
            self.file.done = lines.offset + start
        end = start + lines.offset
        if pending:
            self._deliver_records(pending, chunk_start, end)
        if not lines.ended_with_newline:
            self.file.problems.add(
                "the file ends in the middle of a line: its last record may be cut off (truncated file?)",
                line=first_line + lines.lines_read - 1,
            )
        return end, first_line + lines.lines_read

    def _deliver_records(self, records: list[LogRecord], start: int, end: int) -> None:
        assert self.texts is not None
        topics = [record.topics for record in records]
        robots = [record.robot for record in records]
        self._hand_over(
            IndexedChunk(
                array("q", [clamped(record.stamp_ns) for record in records]),
                array("B", [min(max(record.level, 0), 255) for record in records]),
                self._column("nodes", [record.node for record in records]),
                self._column("files", [record.file for record in records]),
                self._column("functions", [record.function for record in records]),
                IdColumn(None, [self.file.source]),
                array("I", [min(max(record.line, 0), UINT32_MAX) for record in records]),
                start,
                end,
                self.texts,
                self._column("topics", topics) if any(topics) else None,
                self._column("robots", robots) if any(robots) else None,
            ),
            len(records),
        )

    def _column(self, name: str, strings: list[str]) -> IdColumn:
        """Strings as ids into a list of this file's own (one for each column)."""
        ids, names = self._names.setdefault(name, ({}, []))
        found = []
        for text in strings:
            ident = ids.get(text)
            if ident is None:
                ident = ids[text] = len(names)
                names.append(text)
            found.append(ident)
        return IdColumn(array("I", found), names)

    def _hand_over(self, part: IndexedChunk, count: int) -> None:
        self.records += count
        self.deliver(part)

    def _shortened(self, size: int, at: int) -> None:
        self.file.problems.add(
            f"the file got shorter while it was read ({size:,} bytes, {at:,} read): read no further;"
            " the messages of what it held past its new end can no longer be shown"
        )


class _OffsetLines(TextLines):
    """Lines from byte ``base`` of a file, numbered from ``first_line``, that can say where a
    line they gave begins (``offset_of``)."""

    def __init__(self, stream: BinaryIO, file: LogFile, base: int, first_line: int) -> None:
        super().__init__(stream, file.problems)
        self._base = base
        self._shift = first_line - 1
        #: (offset, first line, bytes) of the blocks of lines read, since the oldest still asked about.
        self._blocks: deque[tuple[int, int, bytes]] = deque()

    def __iter__(self) -> Iterator[tuple[int, str]]:
        shift = self._shift
        for number, text in super().__iter__():
            yield number + shift, text

    def _decode(self, data: bytes, first_line: int) -> str:
        self._blocks.append((self._base + self.offset, first_line + self._shift, data))
        return super()._decode(data, first_line + self._shift)

    def offset_of(self, line: int) -> int:
        """Where line ``line`` (given already) begins in the file."""
        blocks = self._blocks
        while len(blocks) > 1 and blocks[1][1] <= line:
            blocks.popleft()
        offset, first, data = blocks[0]
        at = 0
        for _ in range(line - first):
            at = data.index(b"\n", at) + 1
        return offset + at
