"""A full chunk as bytes (what the store writes to disk), and those bytes as a chunk again.

A spilled chunk is one blob: a header that says what the chunk holds without reading the
rest (its records, its stamps' span, its records per severity: ``ColdChunk``), its columns
(stamps, levels, line numbers and string ids) joined and LZ4-compressed, then its
messages: a ``PackedTexts``' compressed text as it is (no work: it was compressed when the
chunk filled) and where each message starts, or, for texts that hold NUL (rare), their
lengths and text compressed. A chunk read from a log file by its index keeps no messages
here: the header names the file and the bytes (``FileTexts``), read again when needed.
"""

from __future__ import annotations

import struct
from array import array
from dataclasses import dataclass

from ..levels import MESSAGE_SEVERITIES, severity_bucket
from .chunk import Chunk
from .packed_texts import PackedTexts, compress_bytes, decompress_bytes

#: count, flags, columns' bytes, columns compressed, texts' bytes, first and last record's stamps,
#: records per severity (DEBUG .. FATAL); then, for texts in a file, its number and bytes.
_HEADER = struct.Struct("<IIIIIqq5I")
_FILE = struct.Struct("<I?qq")
_WIDE = {"lines": 1, "nodes": 2, "files": 4, "functions": 8, "sources": 16, "topics": 32, "robots": 64}
_HAS_TOPICS, _HAS_ROBOTS, _LISTED, _IN_FILE = 128, 256, 512, 1024
_IDS = ("lines", "nodes", "files", "functions", "sources")
_SLOT = {level: MESSAGE_SEVERITIES.index(severity_bucket(level)) for level in range(256)}


@dataclass(frozen=True, slots=True)
class FileTexts:
    """Where a chunk's messages are in a log file: ``source`` (the store's number for the
    file's reader, ``LogStore.text_sources``), bytes ``start:end``; ``verbatim``: each message
    is those bytes' own (no colour codes taken out, nothing replaced), so a text no byte of
    the range holds is in no message of the chunk."""

    source: int
    verbatim: bool
    start: int
    end: int


class ColdChunk:
    """A chunk on disk, as the store keeps it in memory: where its blob is and what its
    header says (a few dozen bytes, whatever the chunk holds)."""

    __slots__ = ("count", "file_texts", "first_stamp", "last_stamp", "length", "offset", "segment", "severities")

    def __init__(self, segment: int, offset: int, length: int, header: bytes) -> None:
        self.segment, self.offset, self.length = segment, offset, length
        count, flags, _raw, _packed, _texts, first, last, *severities = _HEADER.unpack_from(header)
        self.count: int = count
        #: The stamps of its first and last records.
        self.first_stamp, self.last_stamp = first, last
        #: Records per severity, DEBUG .. FATAL (as ``MESSAGE_SEVERITIES``).
        self.severities = tuple(severities)
        self.file_texts = FileTexts(*_FILE.unpack_from(header, _HEADER.size)) if flags & _IN_FILE else None

    def __len__(self) -> int:
        return self.count


def header_size(blob: bytes) -> int:
    """How many of a blob's first bytes ``ColdChunk`` reads."""
    flags: int = _HEADER.unpack_from(blob)[1]
    return _HEADER.size + (_FILE.size if flags & _IN_FILE else 0)


def pack_chunk(chunk: Chunk, file_texts: FileTexts | None = None) -> bytes:
    """``chunk`` (full, or whole at least: nothing is added to it after) as one blob; with
    ``file_texts`` its messages are not in it (they are in that file)."""
    count = len(chunk.levels)
    flags = 0
    parts = [chunk.stamps.tobytes(), chunk.levels.tobytes()]
    for name in _IDS:
        column = getattr(chunk, name)
        if column.typecode != "H":
            flags |= _WIDE[name]
        parts.append(column.tobytes())
    for name, present in (("topics", _HAS_TOPICS), ("robots", _HAS_ROBOTS)):
        column = getattr(chunk, name)
        if column is not None:
            flags |= present | (_WIDE[name] if column.typecode != "H" else 0)
            parts.append(column.tobytes())
    stamps = chunk.stamps
    raw = b"".join(parts)
    columns = compress_bytes(raw, acceleration=4)  # (a tenth larger, a third of the time: as a chunk fills)
    tail = starts = b""
    if file_texts is not None:
        flags |= _IN_FILE
        texts = b""
        tail = _FILE.pack(file_texts.source, file_texts.verbatim, file_texts.start, file_texts.end)
    elif isinstance(chunk.msgs, PackedTexts):
        texts, starts = chunk.msgs.packed, chunk.msgs.starts.tobytes()
    else:
        flags |= _LISTED
        encoded = [text.encode("utf-8", "surrogatepass") for text in chunk.msgs]
        texts = compress_bytes(array("I", map(len, encoded)).tobytes() + b"".join(encoded))
    kept = chunk.severities
    if kept is not None and sum(kept.values()) == count:  # counted as the records came
        severities = [kept.get(int(severity), 0) for severity in MESSAGE_SEVERITIES]
    else:
        severities = [0] * len(MESSAGE_SEVERITIES)
        levels = chunk.levels.tobytes()
        for level in set(levels):
            severities[_SLOT[level]] += levels.count(level)
    header = _HEADER.pack(
        count, flags, len(raw), len(columns), len(texts), *(stamps[0], stamps[-1]) if count else (0, 0), *severities
    )
    return header + tail + columns + texts + starts


def unpack_chunk(blob: bytes) -> tuple[Chunk, FileTexts | None]:
    """The chunk of a blob ``pack_chunk`` made (its messages left out when they are in a file)."""
    count, flags, raw_size, packed_size, texts_size, *_rest = _HEADER.unpack_from(blob)
    at = header_size(blob)
    file_texts = FileTexts(*_FILE.unpack_from(blob, _HEADER.size)) if flags & _IN_FILE else None
    raw = decompress_bytes(blob[at : at + packed_size])
    if len(raw) != raw_size:
        raise ValueError("a spilled chunk's columns are damaged")
    at += packed_size
    chunk = Chunk()
    place = 0

    def take(typecode: str) -> array:
        nonlocal place
        column = array(typecode)
        size = column.itemsize * count
        column.frombytes(raw[place : place + size])
        place += size
        return column

    chunk.stamps = take("q")
    chunk.levels = take("B")
    for name in _IDS:
        setattr(chunk, name, take("I" if flags & _WIDE[name] else "H"))
    if flags & _HAS_TOPICS:
        chunk.topics = take("I" if flags & _WIDE["topics"] else "H")
    if flags & _HAS_ROBOTS:
        chunk.robots = take("I" if flags & _WIDE["robots"] else "H")
    texts = blob[at : at + texts_size]
    if flags & _IN_FILE:
        chunk.msgs = []
    elif flags & _LISTED:
        data = decompress_bytes(texts)
        lengths = array("I")
        lengths.frombytes(data[: 4 * count])
        messages, place = [], 4 * count
        for length in lengths:
            messages.append(data[place : place + length].decode("utf-8", "surrogatepass"))
            place += length
        chunk.msgs = messages
    else:
        starts = array("I")
        starts.frombytes(blob[at + texts_size : at + texts_size + 4 * (count + 1)])
        chunk.msgs = PackedTexts.from_packed(texts, starts)
    return chunk, file_texts
