"""The bounded, append-only log store.

Records are kept column by column in fixed-size chunks: numbers in ``array``s, the
repeated strings (node, file, function, source) as ids into string tables, messages as
``str``. A million records cost about a third of what a million record objects would,
and dropping the oldest chunk when the bound is passed costs O(1).

Every record gets a sequence number (``seq``) in arrival order; a seq never changes and
is never reused, so views and caches key on it. ``first_seq`` is the oldest record
still kept and ``end_seq`` the number the next record will get.
"""

from __future__ import annotations

from array import array
from collections import deque
from collections.abc import Iterable, Iterator
from typing import NamedTuple

from .levels import MESSAGE_SEVERITIES, severity_bucket
from .record import LogRecord

CHUNK_SIZE = 4096
DEFAULT_MAX_MESSAGES = 1_000_000


class StringTable:
    """Interns repeated strings to small integer ids (and back)."""

    __slots__ = ("_ids", "_strings")

    def __init__(self) -> None:
        self._ids: dict[str, int] = {}
        self._strings: list[str] = []

    def id_of(self, text: str) -> int:
        found = self._ids.get(text)
        if found is None:
            found = self._ids[text] = len(self._strings)
            self._strings.append(text)
        return found

    def __getitem__(self, ident: int) -> str:
        return self._strings[ident]

    def __len__(self) -> int:
        return len(self._strings)

    def __iter__(self) -> Iterator[str]:
        return iter(self._strings)


class Chunk:
    """Up to ``CHUNK_SIZE`` consecutive records, one array or list per field."""

    __slots__ = ("stamps", "levels", "lines", "nodes", "files", "functions", "sources", "msgs")

    def __init__(self) -> None:
        self.stamps = array("q")
        self.levels = array("B")
        self.lines = array("L")
        self.nodes = array("L")
        self.files = array("L")
        self.functions = array("L")
        self.sources = array("L")
        self.msgs: list[str] = []

    def __len__(self) -> int:
        return len(self.msgs)


class ChunkSpan(NamedTuple):
    """A run of stored records inside one chunk: offsets ``lo:hi``, the first seq ``seq``."""

    chunk: Chunk
    lo: int
    hi: int
    seq: int


_BUCKET = {level: int(severity_bucket(level)) for level in range(256)}
_INT64_MAX = (1 << 63) - 1


class LogStore:
    """Holds up to ``max_messages`` records, dropping the oldest beyond that."""

    def __init__(self, max_messages: int = DEFAULT_MAX_MESSAGES) -> None:
        if max_messages < 1:
            raise ValueError("max_messages must be at least 1")
        self.max_messages = max_messages
        self.nodes = StringTable()
        self.files = StringTable()
        self.functions = StringTable()
        self.sources = StringTable()
        self._chunks: deque[Chunk] = deque()
        self._base_seq = 0  # seq of the first record of self._chunks[0]; all but the last are full
        self.first_seq = 0
        self.end_seq = 0
        #: Records kept per message severity (DEBUG .. FATAL).
        self.counts: dict[int, int] = {int(s): 0 for s in MESSAGE_SEVERITIES}
        #: Records dropped at the bound since the start.
        self.evicted = 0

    def __len__(self) -> int:
        return self.end_seq - self.first_seq

    def __contains__(self, seq: int) -> bool:
        return self.first_seq <= seq < self.end_seq

    def extend(self, records: Iterable[LogRecord]) -> range:
        """Append records (assigning their ``seq``); returns the range of new seqs."""
        start = self.end_seq
        seq = start
        chunks = self._chunks
        counts = self.counts
        node_id, file_id = self.nodes.id_of, self.files.id_of
        function_id, source_id = self.functions.id_of, self.sources.id_of
        chunk = chunks[-1] if chunks and len(chunks[-1]) < CHUNK_SIZE else None
        for record in records:
            if chunk is None or len(chunk.msgs) >= CHUNK_SIZE:
                chunk = Chunk()
                chunks.append(chunk)
            level = min(max(int(record.level), 0), 255)
            chunk.stamps.append(min(max(int(record.stamp_ns), -_INT64_MAX), _INT64_MAX))
            chunk.levels.append(level)
            chunk.lines.append(min(max(int(record.line), 0), 0xFFFFFFFF))
            chunk.nodes.append(node_id(record.node))
            chunk.files.append(file_id(record.file))
            chunk.functions.append(function_id(record.function))
            chunk.sources.append(source_id(record.source))
            chunk.msgs.append(record.msg)
            counts[_BUCKET[level]] += 1
            record.seq = seq
            seq += 1
        self.end_seq = seq
        if len(self) > self.max_messages:
            self._evict_to(self.end_seq - self.max_messages)
        return range(max(start, self.first_seq), self.end_seq)

    def append(self, record: LogRecord) -> int:
        """Append one record; returns its seq."""
        self.extend((record,))
        return record.seq

    def get(self, seq: int) -> LogRecord:
        """The record with this seq; ``KeyError`` if it was evicted or never stored."""
        if not self.first_seq <= seq < self.end_seq:
            raise KeyError(seq)
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        chunk = self._chunks[number]
        return LogRecord(
            stamp_ns=chunk.stamps[offset],
            level=chunk.levels[offset],
            node=self.nodes[chunk.nodes[offset]],
            msg=chunk.msgs[offset],
            file=self.files[chunk.files[offset]],
            function=self.functions[chunk.functions[offset]],
            line=chunk.lines[offset],
            source=self.sources[chunk.sources[offset]],
            seq=seq,
        )

    def level_of(self, seq: int) -> int:
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        return self._chunks[number].levels[offset]

    def __iter__(self) -> Iterator[LogRecord]:
        return self.records(self.first_seq, self.end_seq)

    def records(self, start: int, stop: int) -> Iterator[LogRecord]:
        """Records with ``start <= seq < stop`` (clamped to what is kept), oldest first."""
        for seq in range(max(start, self.first_seq), min(stop, self.end_seq)):
            yield self.get(seq)

    def spans(self, start: int, stop: int, *, newest_first: bool = False) -> Iterator[ChunkSpan]:
        """The kept records of ``start:stop`` as per-chunk spans, for column-wise scans."""
        start, stop = max(start, self.first_seq), min(stop, self.end_seq)
        if start >= stop:
            return
        origin = self._base_seq
        first, last = (start - origin) // CHUNK_SIZE, (stop - 1 - origin) // CHUNK_SIZE
        numbers = range(last, first - 1, -1) if newest_first else range(first, last + 1)
        for number in numbers:
            base = origin + number * CHUNK_SIZE
            lo = max(start, base) - base
            hi = min(stop, base + CHUNK_SIZE) - base
            yield ChunkSpan(self._chunks[number], lo, hi, base + lo)

    def clear(self) -> None:
        """Drop every record; numbering carries on where it was."""
        self._chunks.clear()
        self._base_seq = self.first_seq = self.end_seq
        for key in self.counts:
            self.counts[key] = 0

    def _evict_to(self, new_first: int) -> None:
        counts = self.counts
        for span in self.spans(self.first_seq, new_first):
            for level in span.chunk.levels[span.lo : span.hi]:
                counts[_BUCKET[level]] -= 1
        self.evicted += new_first - self.first_seq
        self.first_seq = new_first
        while self._chunks and self._base_seq + CHUNK_SIZE <= new_first:
            self._chunks.popleft()
            self._base_seq += CHUNK_SIZE
