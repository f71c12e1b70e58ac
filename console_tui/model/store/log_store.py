"""The bounded, append-only log store.

Records are kept column by column in fixed-size chunks: numbers in ``array``s, the
repeated strings (node, file, function, source) as ids into string tables, messages as
``str``; ROS 1's ``topics`` as ids too, in an array made only for chunks that have some
(nothing for ROS 2), and so the ``robot`` a record came from (only when the console reads a
fleet: several ROS 2 domains or ROS 1 masters, or files named for their robots). Ids and line numbers take 2 bytes while they fit (a chunk's column widens to 4
when one does not); a full chunk keeps its messages joined in one string, compressed
(``PackedTexts``), so a message costs about a third of its text and 4 bytes. Dropping the oldest chunk
when the bound is passed costs O(1). ``extend`` takes one shape, ``RecordColumns`` (a batch
already in columns, as every source hands them over), and works column by column without a
Python step per record.

Every record gets a sequence number (``seq``) in arrival order; a seq never changes and
is never reused, so views and caches key on it. ``first_seq`` is the oldest record
still kept and ``end_seq`` the number the next record will get. The one exception is
``rewrite_from``: the newest records put in another order (a late history placed by its
stamp, ``late_records.py``), or older ones put before them (``put_before``: a log warehouse's
older page); whoever keys on their seqs is told first (``rewind_listeners``).
"""

from __future__ import annotations

from array import array
from collections import Counter, deque
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import Any, NamedTuple

from ..levels import MESSAGE_SEVERITIES, severity_bucket
from .packed_texts import PackedTexts, pack
from .record import LogRecord
from .record_batch import RecordColumns

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

    def ids_of(self, texts: Sequence[str]) -> list[int]:
        """``id_of`` for many strings at once (the common case, all known, at C speed)."""
        found = list(map(self._ids.get, texts))
        if None in found:
            id_of = self.id_of
            return [ident if ident is not None else id_of(text) for ident, text in zip(found, texts, strict=False)]
        return found  # type: ignore[return-value]  # no None in it

    def __getitem__(self, ident: int) -> str:
        return self._strings[ident]

    def __len__(self) -> int:
        return len(self._strings)

    def __iter__(self) -> Iterator[str]:
        return iter(self._strings)

    def __contains__(self, text: object) -> bool:
        return text in self._ids


class Chunk:
    """Up to ``CHUNK_SIZE`` consecutive records, one array or sequence per field.

    ``lines`` and the id columns are arrays of 2-byte items ("H") or, once a value did
    not fit, 4-byte ones ("I"). ``msgs`` is a list while the chunk fills, then (sealed)
    usually a ``PackedTexts``: read it as a sequence of ``str`` (a slice is a list).
    """

    __slots__ = ("files", "functions", "levels", "lines", "msgs", "nodes", "robots", "sources", "stamps", "topics")

    def __init__(self) -> None:
        self.stamps = array("q")
        self.levels = array("B")
        self.lines = array("H")
        self.nodes = array("H")
        self.files = array("H")
        self.functions = array("H")
        self.sources = array("H")
        self.msgs: list[str] | PackedTexts = []
        #: Ids of ROS 1 ``topics``; made only once a record of the chunk has some (ROS 2 never does).
        self.topics: array | None = None
        #: Ids of the records' ``robot``; made only once a record of the chunk names one.
        self.robots: array | None = None

    def __len__(self) -> int:
        return len(self.msgs)

    def seal(self) -> None:
        """The chunk is full: keep its messages packed (compressed)."""
        if isinstance(self.msgs, list):
            self.msgs = pack(self.msgs)


class ChunkSpan(NamedTuple):
    """A run of stored records inside one chunk: offsets ``lo:hi``, the first seq ``seq``."""

    chunk: Chunk
    lo: int
    hi: int
    seq: int


_BUCKET = {level: int(severity_bucket(level)) for level in range(256)}
_INT64_MAX = (1 << 63) - 1
_UINT32_MAX = 0xFFFFFFFF


def _clamp(value: Any, low: int, high: int) -> int:
    return min(max(int(value), low), high)


def _extended(column: array, values: Iterable[int]) -> array:
    """``column`` with ``values`` appended, widened from 2-byte to 4-byte items if one needs it.

    ``OverflowError`` or ``TypeError`` (and ``column`` unchanged) for a value it cannot hold."""
    if isinstance(values, array) and values.typecode == column.typecode:
        column.extend(values)
        return column
    if isinstance(values, bytes) and column.typecode == "B":
        column.frombytes(values)
        return column
    items = values.tolist() if isinstance(values, array) else values if isinstance(values, list) else list(values)
    try:
        column.fromlist(items)  # all or nothing
    except OverflowError:
        if column.typecode != "H":
            raise
        column = array("I", column)
        column.fromlist(items)
    return column


def _optional_ids(
    column: array | None, before: int, table: StringTable, texts: Sequence[str] | None, count: int
) -> array | None:
    """An optional id column (``topics``, ``robots``) with ``count`` more records' ids: made
    (id 0 for the ``before`` records already in the chunk) when ``texts`` is the first to have any."""
    if texts is not None:
        if column is None:
            column = array("H", bytes(2 * before))
        return _extended(column, table.ids_of(texts))
    if column is not None:
        return _extended(column, [0] * count)
    return None


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
        self.robots = StringTable()
        self.robots.id_of("")  # id 0: no robot
        self._chunks: deque[Chunk] = deque()
        self._base_seq = 0  # seq of the first record of self._chunks[0]; all but the last are full
        self.first_seq = 0
        self.end_seq = 0
        #: Records kept per message severity (DEBUG .. FATAL).
        self.counts: dict[int, int] = {int(s): 0 for s in MESSAGE_SEVERITIES}
        #: Records dropped at the bound since the start.
        self.evicted = 0
        #: Called as ``listener(first, new_first)`` just before the records ``first:new_first``
        #: are dropped at the bound: they can still be read, and nothing else has changed yet.
        self.evict_listeners: list[Callable[[int, int], None]] = []
        #: Called as ``listener(start)`` just before the records from ``start`` on are written
        #: again in another order (``rewrite_from``): they can still be read.
        self.rewind_listeners: list[Callable[[int], None]] = []

    def __len__(self) -> int:
        return self.end_seq - self.first_seq

    def __contains__(self, seq: int) -> bool:
        return self.first_seq <= seq < self.end_seq

    def extend(self, columns: RecordColumns) -> range:
        """Append a batch of records; returns the range of their seqs (those still kept)."""
        count = len(columns)
        start = self.end_seq
        chunks = self._chunks
        done = 0
        while done < count:
            if not chunks or len(chunks[-1]) >= CHUNK_SIZE:
                chunks.append(Chunk())
            chunk = chunks[-1]
            room = CHUNK_SIZE - len(chunk)
            piece = columns if done == 0 and count <= room else columns.slice(done, done + room)
            self._append_columns(chunk, piece)
            done += len(piece)
            if len(chunk) >= CHUNK_SIZE:
                chunk.seal()
        self.end_seq = start + count
        if len(self) > self.max_messages:
            self._evict_to(self.end_seq - self.max_messages)
        return range(max(start, self.first_seq), self.end_seq)

    def _append_columns(self, chunk: Chunk, piece: RecordColumns) -> None:
        """Add ``piece`` (which fits in ``chunk``) column by column."""
        levels = piece.levels
        try:
            chunk.stamps = _extended(chunk.stamps, piece.stamps)
        except (OverflowError, TypeError):
            chunk.stamps.fromlist([_clamp(v, -_INT64_MAX, _INT64_MAX) for v in piece.stamps])
        try:
            chunk.levels = _extended(chunk.levels, levels)
        except (OverflowError, TypeError):
            levels = [_clamp(v, 0, 255) for v in levels]
            chunk.levels.fromlist(levels)
        try:
            chunk.lines = _extended(chunk.lines, piece.lines)
        except (OverflowError, TypeError):
            chunk.lines = _extended(chunk.lines, [_clamp(v, 0, _UINT32_MAX) for v in piece.lines])
        chunk.nodes = _extended(chunk.nodes, self.nodes.ids_of(piece.nodes))
        chunk.files = _extended(chunk.files, self.files.ids_of(piece.files))
        chunk.functions = _extended(chunk.functions, self.functions.ids_of(piece.functions))
        chunk.sources = _extended(chunk.sources, self.sources.ids_of(piece.sources))
        chunk.topics = _optional_ids(chunk.topics, len(chunk.msgs), self.topics, piece.topics, len(piece))
        chunk.robots = _optional_ids(chunk.robots, len(chunk.msgs), self.robots, piece.robots, len(piece))
        msgs = chunk.msgs
        assert isinstance(msgs, list), "only the newest chunk grows, and it is never sealed"
        msgs.extend(piece.msgs)
        counts = self.counts
        for level, number in Counter(levels).items():
            counts[_BUCKET[level]] += number

    def rewrite_from(self, start: int, columns: RecordColumns) -> range:
        """Replace the records from seq ``start`` on with ``columns`` (the same records, in
        another order, and new ones after them); returns the range of seqs written."""
        start = min(max(start, self.first_seq), self.end_seq)
        for listener in self.rewind_listeners:
            listener(start)
        self._truncate_to(start)
        self.extend(columns)
        return range(start, self.end_seq)

    def put_before(self, columns: RecordColumns) -> int:
        """Put ``columns``, records older than every kept one, before them: what
        ``rewrite_from(first_seq, joined([columns, kept]))`` does (the listeners told, the kept
        records' seqs moved up by the number returned), at the cost of ``columns`` and one
        chunk: the kept chunks but the first are kept whole (the first chunk before them
        starts with unused places, as after an eviction)."""
        first, chunks = self.first_seq, self._chunks
        if not len(columns):
            return 0
        if len(chunks) < 2 or len(columns) + 2 * CHUNK_SIZE > self.max_messages:  # nothing to keep whole
            self.rewrite_from(first, RecordColumns.joined([columns, self.columns(first, self.end_seq)]))
            return len(columns)
        base, end = self._base_seq, self.end_seq
        front = RecordColumns.joined([columns, self.columns(first, base + CHUNK_SIZE)])
        pad = -len(front) % CHUNK_SIZE  # unused places, so that the kept chunks stay whole
        for listener in self.rewind_listeners:
            listener(first)
        kept, counts = list(chunks)[1:], dict(self.counts)
        self._chunks = deque()
        self.first_seq = self.end_seq = base
        self.extend(front.reordered([0] * pad + list(range(len(front)))))
        self._chunks.extend(kept)
        shift = pad + len(columns) - (first - base)
        self.first_seq, self.end_seq = base + pad, end + shift
        self.counts.update(counts)  # the kept records' counts, and the new ones'
        for level, number in Counter(columns.levels).items():
            self.counts[_BUCKET[level]] += number
        if len(self) > self.max_messages:
            self._evict_to(self.end_seq - self.max_messages)
        return shift

    def columns(self, start: int, stop: int) -> RecordColumns:
        """The kept records of ``start:stop`` as one batch of columns."""
        spans = list(self.spans(start, stop))
        parts = []
        for chunk, lo, hi, _seq in spans:
            ids = (chunk.nodes[lo:hi], chunk.files[lo:hi], chunk.functions[lo:hi], chunk.sources[lo:hi])
            tables = (self.nodes, self.files, self.functions, self.sources)
            nodes, files, functions, sources = (
                list(map(table.__getitem__, part)) for table, part in zip(tables, ids, strict=True)
            )
            optional = [
                None if column is None else list(map(table.__getitem__, column[lo:hi]))
                for column, table in ((chunk.topics, self.topics), (chunk.robots, self.robots))
            ]
            parts.append(
                RecordColumns(
                    chunk.stamps[lo:hi].tolist(),
                    chunk.levels[lo:hi].tolist(),
                    nodes,
                    list(chunk.msgs[lo:hi]),
                    files,
                    functions,
                    chunk.lines[lo:hi].tolist(),
                    sources,
                    *optional,
                )
            )
        if not parts:
            return RecordColumns([], [], [], [], [], [], [], [])
        return RecordColumns.joined(parts)

    def _truncate_to(self, end: int) -> None:
        """Drop the records from seq ``end`` on (the newest); numbering goes on from ``end``."""
        counts = self.counts
        for span in self.spans(end, self.end_seq):
            for level, number in Counter(span.chunk.levels[span.lo : span.hi]).items():
                counts[_BUCKET[level]] -= number
        chunks = self._chunks
        while chunks and self._base_seq + CHUNK_SIZE * (len(chunks) - 1) >= end:
            chunks.pop()
        if chunks:
            chunk, keep = chunks[-1], end - self._base_seq - CHUNK_SIZE * (len(chunks) - 1)
            for name in ("stamps", "levels", "lines", "nodes", "files", "functions", "sources", "topics", "robots"):
                column = getattr(chunk, name)
                if column is not None:
                    del column[keep:]
            chunk.msgs = list(chunk.msgs[:keep])
        else:
            self._base_seq = end
        self.end_seq = end

    def extend_records(self, records: Iterable[LogRecord]) -> range:
        """``extend`` for records made one by one (tests, a rule's sample), setting their ``seq``."""
        objects = records if isinstance(records, list) else list(records)
        added = self.extend(RecordColumns.from_records(objects))
        for seq, record in enumerate(objects, added.stop - len(objects)):
            record.seq = seq
        return added

    def append(self, record: LogRecord) -> int:
        """Append one record; returns its seq."""
        self.extend_records((record,))
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
            robot=self.robots[chunk.robots[offset]] if chunk.robots is not None else "",
        )

    def level_of(self, seq: int) -> int:
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        return self._chunks[number].levels[offset]

    def stamp_of(self, seq: int) -> int:
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        return self._chunks[number].stamps[offset]

    def node_id_of(self, seq: int) -> int:
        """The id of the record's node in ``nodes``."""
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        return self._chunks[number].nodes[offset]

    def robot_id_of(self, seq: int) -> int:
        """The id of the record's robot in ``robots`` (0: none)."""
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        robots = self._chunks[number].robots
        return robots[offset] if robots is not None else 0

    def __iter__(self) -> Iterator[LogRecord]:
        return self.records(self.first_seq, self.end_seq)

    def records(self, start: int, stop: int) -> Iterator[LogRecord]:
        """Records with ``start <= seq < stop`` (clamped to what is kept), oldest first."""
        for seq in range(max(start, self.first_seq), min(stop, self.end_seq)):
            yield self.get(seq)

    def chunk_start(self, seq: int) -> int:
        """The first seq of the chunk that holds (or would hold) ``seq``."""
        return seq - (seq - self._base_seq) % CHUNK_SIZE

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
        for listener in self.evict_listeners:
            listener(self.first_seq, new_first)
        counts = self.counts
        for span in self.spans(self.first_seq, new_first):
            for level, number in Counter(span.chunk.levels[span.lo : span.hi]).items():
                counts[_BUCKET[level]] -= number
        self.evicted += new_first - self.first_seq
        self.first_seq = new_first
        while self._chunks and self._base_seq + CHUNK_SIZE <= new_first:
            self._chunks.popleft()
            self._base_seq += CHUNK_SIZE
