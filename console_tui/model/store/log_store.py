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

Full chunks can leave memory for disk (``spill``, a ``ChunkSpill``): the store then keeps a
``ColdChunk`` for each (a few dozen bytes) and reads the chunk back when it is read
(``_chunk``), so a history of tens of millions of records holds a few MB; ``max_messages``
then bounds the records on disk, the oldest going a whole chunk at a time. Without a spill, or
while writing to disk fails (a full disk: ``spill_problem``), memory holds at most
``memory_bound`` records, the oldest dropped first (those on disk among them).

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
from collections.abc import Callable, Iterable, Iterator

from ..levels import MESSAGE_SEVERITIES, severity_bucket
from .chunk import CHUNK_SIZE, Chunk, ChunkSpan, StringTable, Tables, extended
from .chunk_blob import ColdChunk, FileTexts
from .chunk_spill import ChunkSpill
from .indexed_chunk import FileChunk, IdColumn, IndexedChunk
from .record import LogRecord
from .record_batch import RecordColumns

__all__ = ["CHUNK_SIZE", "DEFAULT_MAX_MESSAGES", "Chunk", "ChunkSpan", "LogStore", "StringTable"]

#: Records kept at most (on disk, with a spill).
DEFAULT_MAX_MESSAGES = 50_000_000
#: Records kept in memory at most (without a spill, or while writing to disk fails).
MEMORY_BOUND = 1_000_000
_SEVERITIES = tuple(int(severity) for severity in MESSAGE_SEVERITIES)
_BUCKET = {level: int(severity_bucket(level)) for level in range(256)}


class LogStore:
    """Holds up to ``max_messages`` records (``memory_bound`` of them in memory), dropping
    the oldest beyond that."""

    def __init__(
        self,
        max_messages: int = DEFAULT_MAX_MESSAGES,
        *,
        spill: ChunkSpill | None = None,
        memory_bound: int = MEMORY_BOUND,
    ) -> None:
        if max_messages < 1:
            raise ValueError("max_messages must be at least 1")
        self.max_messages = max_messages
        self.memory_bound = max(memory_bound, CHUNK_SIZE)
        self.spill = spill
        #: Why there is no spill when one was wanted (its directory refused), for the status line.
        self.memory_reason = ""
        #: The files read by index whose chunks are kept (``extend_indexed``): numbers by
        #: their ``TextSource``'s id, and their strings' ids in the store's tables.
        self._text_sources: dict[int, int] = {}
        self._lookups: dict[tuple[int, str], list[int]] = {}
        self._same_ids: dict[tuple[int, str], bool] = {}
        #: The strings the chunks name by id (``nodes``, ``files``, ... are its tables).
        self.tables = Tables()
        tables = self.tables
        self.nodes, self.files, self.functions = tables.nodes, tables.files, tables.functions
        self.sources, self.topics, self.robots = tables.sources, tables.topics, tables.robots
        self._chunks: deque[Chunk | ColdChunk] = deque()
        self._base_seq = 0  # seq of the first record of self._chunks[0]; all but the last are full
        self._cold = 0  # self._chunks[:_cold] are on disk (ColdChunk), the rest in memory
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
        if spill is not None:
            spill.attach(tables.by_name())

    @property
    def bound(self) -> int:
        """The most records kept: ``max_messages``, or ``memory_bound`` without a spill."""
        return self.max_messages if self.spill is not None else min(self.max_messages, self.memory_bound)

    @property
    def spill_problem(self) -> str:
        """Why full chunks stay in memory now (writing to disk failed), or ""."""
        return self.spill.problem if self.spill is not None else ""

    @property
    def on_disk(self) -> int:
        """Records kept on disk."""
        return self._cold * CHUNK_SIZE

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
            assert isinstance(chunk, Chunk), "the newest chunk is in memory (full ones only are on disk)"
            room = CHUNK_SIZE - len(chunk)
            piece = columns if done == 0 and count <= room else columns.slice(done, done + room)
            for level, number in chunk.add_columns(piece, self.tables).items():
                self.counts[level] += number
            done += len(piece)
            if len(chunk) >= CHUNK_SIZE:
                chunk.seal()
        self.end_seq = start + count
        if self.spill is not None and self._cold < len(chunks) and len(chunks[self._cold]) >= CHUNK_SIZE:
            self._spill_full()
        bound = self.bound
        if len(self) > bound:
            self._drop_beyond(bound)
        elif self.spill is not None and (len(chunks) - self._cold) * CHUNK_SIZE > self.memory_bound:
            # Writing to disk fails: memory keeps the newest records, and all older ones go.
            self._evict_to(max(self.end_seq - self.memory_bound, self.first_seq))
        return range(max(start, self.first_seq), self.end_seq)

    def extend_indexed(self, part: IndexedChunk) -> range:
        """Append a chunk of a log file read by its index: its columns go to disk and its
        messages stay in the file (read from there when read), when the store has a disk and
        the chunk fills one of its own; otherwise its messages are read now and it is added
        as any batch (``extend``)."""
        spill, chunks = self.spill, self._chunks
        if spill is not None:
            self._spill_full()
        whole = len(part) == CHUNK_SIZE and self._cold == len(chunks)
        if spill is None or not whole or not spill.writing:
            return self.extend(part.with_messages())
        number = self._text_sources.setdefault(id(part.source), len(self._text_sources))
        spill.text_sources[number] = part.source
        chunk = Chunk()
        chunk.stamps = part.stamps  # (int64: the indexer clamps them as ``extend`` does)
        chunk.levels = part.levels
        chunk.lines = extended(array("H"), part.lines) if part.lines is not None else array("H", bytes(2 * CHUNK_SIZE))
        for name in ("nodes", "files", "functions", "sources", "topics", "robots"):
            column = getattr(part, name)
            if column is not None:
                setattr(chunk, name, self._ids_of(number, name, column))
        base = self.end_seq
        texts = FileTexts(number, part.verbatim, part.start, part.end)
        cold = spill.spill(base, FileChunk.of(chunk, part.source, texts), texts)
        if cold is None:
            return self.extend(part.with_messages())
        chunks.append(cold)
        self._cold += 1
        self.end_seq = base + CHUNK_SIZE
        for severity, count in zip(_SEVERITIES, cold.severities, strict=True):
            self.counts[severity] += count
        if len(self) > self.bound:
            self._drop_beyond(self.bound)
        return range(max(base, self.first_seq), self.end_seq)

    def _ids_of(self, source: int, name: str, column: IdColumn) -> array:
        """A file's column of strings as ids into the store's table ``name``."""
        table: StringTable = getattr(self, name)
        key = (source, name)
        lookup = self._lookups.setdefault(key, [])
        if len(lookup) < len(column.names):
            lookup += table.ids_of(column.names[len(lookup) :])
            self._same_ids[key] = lookup == list(range(len(lookup)))
        if column.ids is None:
            return extended(array("H"), [lookup[0]]) * CHUNK_SIZE
        if self._same_ids.get(key) and column.ids.typecode in "HI":
            return column.ids  # the file's ids are the table's (its strings came first): no mapping
        return extended(array("H"), list(map(lookup.__getitem__, column.ids)))

    def keep_rest(self) -> None:
        """Write the records still in memory to disk as well (the newest chunk too, as it is):
        the session ends, and its history is kept (``--keep-history``). The last call on the store."""
        spill = self.spill
        if spill is None:
            return
        self._spill_full()
        kept, skip = [], 0
        for number, chunk in enumerate(self._chunks):
            cold = chunk if isinstance(chunk, ColdChunk) else None
            if isinstance(chunk, Chunk) and len(chunk):
                cold = spill.spill(self._base_seq + number * CHUNK_SIZE, chunk)
            if cold is not None:
                kept.append(cold)
                skip = skip if number else self.first_seq - self._base_seq  # (the oldest: dropped in part)
        spill.keep_index(kept, skip)

    def _spill_full(self) -> None:
        """Write the full chunks still in memory to disk, oldest first (while that works)."""
        spill, chunks = self.spill, self._chunks
        assert spill is not None
        if not spill.writing:
            return
        while self._cold < len(chunks):
            chunk = chunks[self._cold]
            if not isinstance(chunk, Chunk) or len(chunk) < CHUNK_SIZE:
                return
            cold = spill.spill(self._base_seq + self._cold * CHUNK_SIZE, chunk)
            if cold is None:
                return
            chunks[self._cold] = cold
            self._cold += 1

    def _chunk(self, number: int) -> Chunk:
        """Chunk ``number`` (0: the oldest kept), read back from disk when it is there."""
        chunk = self._chunks[number]
        if isinstance(chunk, Chunk):
            return chunk
        assert self.spill is not None
        return self.spill.warm(self._base_seq + number * CHUNK_SIZE, chunk)

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
        parts = [chunk.columns(lo, hi, self.tables) for chunk, lo, hi, _seq in self.spans(start, stop)]
        if not parts:
            return RecordColumns([], [], [], [], [], [], [], [])
        return RecordColumns.joined(parts)

    def _truncate_to(self, end: int) -> None:
        """Drop the records from seq ``end`` on (the newest); numbering goes on from ``end``."""
        counts = self.counts
        for span in self.spans(end, self.end_seq):
            for level, number in Counter(span.chunk.levels[span.lo : span.hi]).items():
                counts[_BUCKET[level]] -= number
        self._warm_from(end)
        chunks = self._chunks
        while chunks and self._base_seq + CHUNK_SIZE * (len(chunks) - 1) >= end:
            chunks.pop()
        if chunks:
            chunk, keep = chunks[-1], end - self._base_seq - CHUNK_SIZE * (len(chunks) - 1)
            assert isinstance(chunk, Chunk)  # (_warm_from)
            for name in ("stamps", "levels", "lines", "nodes", "files", "functions", "sources", "topics", "robots"):
                column = getattr(chunk, name)
                if column is not None:
                    del column[keep:]
            chunk.msgs = list(chunk.msgs[:keep])
            chunk.severities = None  # (counted again when it is written)
        else:
            self._base_seq = end
        self.end_seq = end

    def _warm_from(self, seq: int) -> None:
        """The chunks from the one holding ``seq`` on are in memory again (to be written anew)."""
        spill = self.spill
        if spill is None:
            return
        first = max((seq - self._base_seq) // CHUNK_SIZE, 0)
        for number in range(first, self._cold):
            base = self._base_seq + number * CHUNK_SIZE
            cold = self._chunks[number]
            assert isinstance(cold, ColdChunk)
            self._chunks[number] = spill.warm(base, cold)
            spill.forget(base, cold)
        self._cold = min(self._cold, first)
        spill.forget_warm_from(self._base_seq + first * CHUNK_SIZE)

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
        chunk = self._chunk(number)
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
        return self._chunk(number).levels[offset]

    def stamp_of(self, seq: int) -> int:
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        return self._chunk(number).stamps[offset]

    def node_id_of(self, seq: int) -> int:
        """The id of the record's node in ``nodes``."""
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        return self._chunk(number).nodes[offset]

    def robot_id_of(self, seq: int) -> int:
        """The id of the record's robot in ``robots`` (0: none)."""
        number, offset = divmod(seq - self._base_seq, CHUNK_SIZE)
        robots = self._chunk(number).robots
        return robots[offset] if robots is not None else 0

    def __iter__(self) -> Iterator[LogRecord]:
        return self.records(self.first_seq, self.end_seq)

    def records(self, start: int, stop: int) -> Iterator[LogRecord]:
        """Records with ``start <= seq < stop`` (clamped to what is kept), oldest first."""
        for seq in range(max(start, self.first_seq), min(stop, self.end_seq)):
            yield self.get(seq)

    def chunk_may_hold(self, seq: int, text: str, lower: bool) -> bool | None:
        """Whether a message of the chunk holding ``seq`` may hold ``text`` (lower-cased ASCII
        when ``lower``), when a log file read by index can say so without the chunk being read
        back (``ChunkSpill.holds``); None when it cannot."""
        number = (seq - self._base_seq) // CHUNK_SIZE
        if not 0 <= number < self._cold or self.spill is None:
            return None
        cold = self._chunks[number]
        assert isinstance(cold, ColdChunk)
        return self.spill.holds(self._base_seq + number * CHUNK_SIZE, cold, text, lower)

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
            yield ChunkSpan(self._chunk(number), lo, hi, base + lo)

    def clear(self) -> None:
        """Drop every record; numbering carries on where it was."""
        self._forget_cold(self._cold)
        self._chunks.clear()
        self._base_seq = self.first_seq = self.end_seq
        for key in self.counts:
            self.counts[key] = 0

    def _drop_beyond(self, bound: int) -> None:
        """Drop the oldest records beyond ``bound``; from the chunks on disk a whole chunk at a
        time (part of one would be read back only to count what goes), so up to
        ``CHUNK_SIZE - 1`` more than needed go there."""
        new_first = self.end_seq - bound
        number = (new_first - 1 - self._base_seq) // CHUNK_SIZE  # the chunk of the last to go
        if number < self._cold:
            new_first = self._base_seq + (number + 1) * CHUNK_SIZE
        self._evict_to(new_first)

    def _evict_to(self, new_first: int) -> None:
        for listener in self.evict_listeners:
            listener(self.first_seq, new_first)
        counts = self.counts
        origin, chunks = self._base_seq, self._chunks
        for number in range((self.first_seq - origin) // CHUNK_SIZE, (new_first - 1 - origin) // CHUNK_SIZE + 1):
            base = origin + number * CHUNK_SIZE
            lo, hi = max(self.first_seq, base) - base, min(new_first, base + CHUNK_SIZE) - base
            whole = chunks[number]
            if isinstance(whole, ColdChunk) and lo == 0 and hi >= whole.count:
                for severity, number_of in zip(_SEVERITIES, whole.severities, strict=True):
                    counts[severity] -= number_of
                continue
            for level, number_of in Counter(self._chunk(number).levels[lo:hi]).items():
                counts[_BUCKET[level]] -= number_of
        self.evicted += new_first - self.first_seq
        self.first_seq = new_first
        gone = 0
        while gone < len(chunks) and self._base_seq + (gone + 1) * CHUNK_SIZE <= new_first:
            gone += 1
        self._forget_cold(min(gone, self._cold))
        for _ in range(gone):
            chunks.popleft()
        self._base_seq += gone * CHUNK_SIZE

    def _forget_cold(self, count: int) -> None:
        """The oldest ``count`` chunks on disk are going."""
        spill = self.spill
        if spill is None:
            return
        for number in range(count):
            cold = self._chunks[number]
            assert isinstance(cold, ColdChunk)
            spill.forget(self._base_seq + number * CHUNK_SIZE, cold)
        self._cold -= count
