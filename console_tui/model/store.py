"""The bounded, append-only log store.

Records are kept column by column in fixed-size chunks: numbers in ``array``s, the
repeated strings (node, file, function, source) as ids into string tables, messages as
``str``; ROS 1's ``topics`` as ids too, in an array made only for chunks that have some
(4 bytes a record there, nothing for ROS 2). A million realistic records cost about 190 MB, 60% of what a million record
objects would (benchmarks/store.py), and dropping the oldest chunk when the bound is
passed costs O(1). ``extend`` works column by column, about 1 us a record.

Every record gets a sequence number (``seq``) in arrival order; a seq never changes and
is never reused, so views and caches key on it. ``first_seq`` is the oldest record
still kept and ``end_seq`` the number the next record will get.
"""

from __future__ import annotations

from array import array
from collections import Counter, deque
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

    def ids_of(self, texts: list[str]) -> list[int]:
        """``id_of`` for many strings at once (the common case, all known, at C speed)."""
        ids = list(map(self._ids.get, texts))
        if None in ids:
            id_of = self.id_of
            ids = [ident if ident is not None else id_of(text) for ident, text in zip(ids, texts, strict=False)]
        return ids

    def __getitem__(self, ident: int) -> str:
        return self._strings[ident]

    def __len__(self) -> int:
        return len(self._strings)

    def __iter__(self) -> Iterator[str]:
        return iter(self._strings)


class Chunk:
    """Up to ``CHUNK_SIZE`` consecutive records, one array or list per field."""

    __slots__ = ("files", "functions", "levels", "lines", "msgs", "nodes", "sources", "stamps", "topics")

    def __init__(self) -> None:
        self.stamps = array("q")
        self.levels = array("B")
        self.lines = array("I")
        self.nodes = array("I")
        self.files = array("I")
        self.functions = array("I")
        self.sources = array("I")
        self.msgs: list[str] = []
        #: Ids of ROS 1 ``topics``; made only once a record of the chunk has some (ROS 2 never does).
        self.topics: array | None = None

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
_UINT32_MAX = 0xFFFFFFFF


def _clamp(value: object, low: int, high: int) -> int:
    return min(max(int(value), low), high)


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
        self.topics = StringTable()
        self.topics.id_of("")  # id 0: no topics
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
        records = records if isinstance(records, list) else list(records)
        start = self.end_seq
        chunks = self._chunks
        done = 0
        while done < len(records):
            if not chunks or len(chunks[-1]) >= CHUNK_SIZE:
                chunks.append(Chunk())
            chunk = chunks[-1]
            piece = records[done : done + CHUNK_SIZE - len(chunk)]
            self._append_columns(chunk, piece)
            done += len(piece)
        for seq, record in enumerate(records, start):
            record.seq = seq
        self.end_seq = start + len(records)
        if len(self) > self.max_messages:
            self._evict_to(self.end_seq - self.max_messages)
        return range(max(start, self.first_seq), self.end_seq)

    def _append_columns(self, chunk: Chunk, piece: list[LogRecord]) -> None:
        """Add ``piece`` (which fits in ``chunk``) column by column."""
        stamps = [r.stamp_ns for r in piece]
        levels = [r.level for r in piece]
        lines = [r.line for r in piece]
        try:  # fromlist adds all or nothing: out-of-range values leave the arrays as they were
            chunk.stamps.fromlist(stamps)
        except (OverflowError, TypeError):
            chunk.stamps.fromlist([_clamp(v, -_INT64_MAX, _INT64_MAX) for v in stamps])
        try:
            chunk.levels.fromlist(levels)
        except (OverflowError, TypeError):
            levels = [_clamp(v, 0, 255) for v in levels]
            chunk.levels.fromlist(levels)
        try:
            chunk.lines.fromlist(lines)
        except (OverflowError, TypeError):
            chunk.lines.fromlist([_clamp(v, 0, _UINT32_MAX) for v in lines])
        chunk.nodes.fromlist(self.nodes.ids_of([r.node for r in piece]))
        chunk.files.fromlist(self.files.ids_of([r.file for r in piece]))
        chunk.functions.fromlist(self.functions.ids_of([r.function for r in piece]))
        chunk.sources.fromlist(self.sources.ids_of([r.source for r in piece]))
        topics = [r.topics for r in piece]
        if chunk.topics is not None or any(topics):
            if chunk.topics is None:
                chunk.topics = array("I", bytes(4 * len(chunk.msgs)))  # the records before: none
            chunk.topics.fromlist(self.topics.ids_of(topics))
        chunk.msgs.extend([r.msg for r in piece])
        counts = self.counts
        for level, number in Counter(levels).items():
            counts[_BUCKET[level]] += number

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
            topics=self.topics[chunk.topics[offset]] if chunk.topics is not None else "",
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
            for level, number in Counter(span.chunk.levels[span.lo : span.hi]).items():
                counts[_BUCKET[level]] -= number
        self.evicted += new_first - self.first_seq
        self.first_seq = new_first
        while self._chunks and self._base_seq + CHUNK_SIZE <= new_first:
            self._chunks.popleft()
            self._base_seq += CHUNK_SIZE
