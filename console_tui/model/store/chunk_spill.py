"""The store's full chunks on disk, and the few read back: what keeps a history's memory bounded.

When a chunk fills, the store hands it to ``ChunkSpill.spill``: it is written to the segment
files (``spill_file.py``) as one blob (``chunk_blob.py``) and the store keeps only its
``ColdChunk`` (where it is, its records' span and severities: a few dozen bytes). Reading a
chunk (``warm``) gives the chunk itself, from the last ``WARM_CHUNKS`` read (the newest
spilled among them) or read back from disk, so the memory a history holds is those chunks
and one ``ColdChunk`` each, whatever the number of records.

Strings the chunks name by id (nodes, files, functions, sources, topics, robots) are
written before the first chunk that needs them, every segment beginning with all of them,
so that a kept history can be read again from its files alone (``reopen.py``).

A write that fails (a full disk, a size limit: ``spill_file.py`` leaves nothing of it) is not
an error for the session: the chunk stays in memory, ``problem`` says why, and writing is
tried again after ``RETRY_S``. A chunk that cannot be read back (its file damaged or gone) is
given as placeholders that say so, never an exception.
"""

from __future__ import annotations

import struct
import time
from array import array
from collections import OrderedDict
from collections.abc import Callable, Mapping

from .chunk import Chunk, StringTable
from .chunk_blob import ColdChunk, FileTexts, header_size, pack_chunk, unpack_chunk
from .indexed_chunk import FileChunk, TextSource
from .spill_file import CHUNK, KEPT, TABLES, SpillFiles, pack_kept

#: Chunks kept in memory after being read back or spilled (about 200 KB each).
WARM_CHUNKS = 48
#: After a failed write, writing is tried again this long after.
RETRY_S = 30.0
_TABLE = struct.Struct("<BII")
#: The store's string tables, in the order their records name them.
TABLE_NAMES = ("nodes", "files", "functions", "sources", "topics", "robots")


class ChunkSpill:
    """Full chunks written to ``files`` and read back, with the last ``warm_chunks`` kept."""

    def __init__(
        self,
        files: SpillFiles,
        *,
        warm_chunks: int = WARM_CHUNKS,
        clock: Callable[[], float] = time.monotonic,
        keep: bool = False,
    ) -> None:
        self.files = files
        self.warm_chunks = warm_chunks
        self.clock = clock
        #: The directory stays when the session ends (``--keep-history``).
        self.keep = keep
        self._warm: OrderedDict[int, Chunk] = OrderedDict()
        self._tables: Mapping[str, StringTable] = {}
        self._written: dict[str, int] = {}
        #: Why the last write failed ("" while writing works).
        self.problem = ""
        self._failed_at: float | None = None
        #: Chunks that could not be read back.
        self.unreadable = 0
        #: What reads the messages of chunks of log files read by index: by ``FileTexts.source``.
        self.text_sources: dict[int, TextSource] = {}
        files.on_new_segment = self._segment_begun

    def attach(self, tables: Mapping[str, StringTable]) -> None:
        """The store's string tables, written to disk as its chunks need them."""
        self._tables = tables

    @property
    def read_problem(self) -> str:
        """Why messages of a file read by index could not be read again (it changed), or ""."""
        return next((source.problem for source in self.text_sources.values() if source.problem), "")

    @property
    def writing(self) -> bool:
        """Chunks are written to disk now (no failure, or the time to try again has come)."""
        return self._failed_at is None or self.clock() - self._failed_at >= RETRY_S

    def spill(self, base: int, chunk: Chunk, file_texts: FileTexts | None = None) -> ColdChunk | None:
        """Write full ``chunk`` (first seq ``base``); its ``ColdChunk``, or None when writing
        failed (``problem`` says why: the chunk stays in memory)."""
        try:
            blob = pack_chunk(chunk, file_texts)
            self.files.make_room(len(blob))  # (a new segment begins with every string: _segment_begun)
            self._write_tables()
            segment, offset = self.files.append(CHUNK, blob)
        except OSError as error:
            self.problem = _describe(error)
            self._failed_at = self.clock()
            return None
        self.problem = ""
        self._failed_at = None
        self._keep_warm(base, chunk)
        return ColdChunk(segment, offset, len(blob), blob[: header_size(blob)])

    def keep_index(self, chunks: list[ColdChunk], skip: int) -> None:
        """Say which chunks the store still held as the session ends (its history kept): those
        it had dropped stay in their segments until the last chunk of each goes, and are not
        read again; ``skip``: the first one's records it had dropped already."""
        try:
            self.files.append(KEPT, pack_kept([(cold.segment, cold.offset) for cold in chunks], skip), hold=False)
        except OSError as error:
            self.problem = _describe(error)  # (read again, the session then holds those chunks too)

    def warm(self, base: int, cold: ColdChunk) -> Chunk:
        """The chunk ``cold`` stands for (first seq ``base``)."""
        chunk = self._warm.get(base)
        if chunk is not None:
            self._warm.move_to_end(base)
            return chunk
        try:
            chunk, file_texts = unpack_chunk(self.files.read(cold.segment, cold.offset, cold.length))
            if file_texts is not None:
                chunk = FileChunk.of(chunk, self.text_sources[file_texts.source], file_texts)
        except (OSError, ValueError, KeyError) as error:
            self.unreadable += 1
            self.problem = f"a chunk of the history on disk cannot be read: {_describe(error)}"
            chunk = lost_chunk(cold, self.problem)
        self._keep_warm(base, chunk)
        return chunk

    def holds(self, base: int, cold: ColdChunk, text: str, lower: bool) -> bool | None:
        """Whether a message of chunk ``cold`` (first seq ``base``) of a log file read by index
        may hold ``text`` (lower-cased ASCII when ``lower``), as the file's bytes say, without
        reading the chunk back; None when they cannot say."""
        texts = cold.file_texts
        if texts is None or not texts.verbatim:
            return None
        warm = self._warm.get(base)
        if isinstance(warm, FileChunk):
            return warm.may_hold(text, lower)
        source = self.text_sources.get(texts.source)
        return None if source is None else source.holds(texts, text.encode("utf-8"), lower)

    def _keep_warm(self, base: int, chunk: Chunk) -> None:
        warm = self._warm
        warm[base] = chunk
        warm.move_to_end(base)
        while len(warm) > self.warm_chunks:
            warm.popitem(last=False)

    def forget(self, base: int, cold: ColdChunk) -> None:
        """The store dropped the chunk: its file goes with the last chunk in it."""
        self._warm.pop(base, None)
        self.files.release(cold.segment)

    def forget_warm_from(self, base: int) -> None:
        """Chunks from seq ``base`` on are written again (the store rewrote its newest records)."""
        for key in [key for key in self._warm if key >= base]:
            del self._warm[key]

    def _segment_begun(self, segment: int) -> None:
        self._written = {}  # every segment starts with all the strings

    def _write_tables(self) -> None:
        parts = []
        for code, name in enumerate(TABLE_NAMES):
            table = self._tables.get(name)
            if table is None:
                continue
            done = self._written.get(name, 0)
            if len(table) > done:
                strings = [table[ident].encode("utf-8", "surrogatepass") for ident in range(done, len(table))]
                lengths = array("I", map(len, strings)).tobytes()
                parts.append(_TABLE.pack(code, done, len(strings)) + lengths + b"".join(strings))
        if parts:
            self.files.append(TABLES, b"".join(parts), hold=False)
            for name in TABLE_NAMES:
                table = self._tables.get(name)
                if table is not None:
                    self._written[name] = len(table)

    @property
    def warm_count(self) -> int:
        return len(self._warm)


def read_tables(blob: bytes) -> list[tuple[str, int, list[str]]]:
    """The strings a ``TABLES`` record holds: (table, first id, strings)."""
    found = []
    at = 0
    while at + _TABLE.size <= len(blob):
        code, first, count = _TABLE.unpack_from(blob, at)
        at += _TABLE.size
        lengths = array("I")
        lengths.frombytes(blob[at : at + 4 * count])
        at += 4 * count
        strings = []
        for length in lengths:
            strings.append(blob[at : at + length].decode("utf-8", "surrogatepass"))
            at += length
        found.append((TABLE_NAMES[code], first, strings))
    return found


def lost_chunk(cold: ColdChunk, why: str) -> Chunk:
    """``cold``'s records as placeholders: its first stamp, INFO, and ``why`` as each message."""
    chunk = Chunk()
    count = cold.count
    chunk.stamps = array("q", [cold.first_stamp]) * count
    chunk.levels = array("B", [20]) * count
    for name in ("lines", "nodes", "files", "functions", "sources"):
        setattr(chunk, name, array("H", bytes(2 * count)))
    chunk.msgs = [f"(lost: {why})"] * count
    return chunk


def _describe(error: BaseException) -> str:
    if isinstance(error, OSError) and error.strerror:
        return error.strerror + (f": {error.filename}" if error.filename else "")
    return str(error) or type(error).__name__
