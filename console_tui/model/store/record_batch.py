"""Records column by column, and packed into bytes to cross from one process to another.

A ``RecordColumns`` is a batch of records held as one sequence per field, the shape the
store keeps them in: adding one to the store costs a few C-level copies instead of a
Python step per record. A live intake running in a child process packs its batches with
a ``BatchPacker`` and the app unpacks them with a ``BatchUnpacker``, which costs it far
less than decoding CDR bytes would (docs/decisions/0005-intake-in-its-own-process.md).

The packed layout (native byte order: both ends are processes of the same machine)::

    u32 count, u32 flags, u32 new strings
    new strings: u32 byte length each, then their UTF-8 bytes
    stamps: int64[count]; lines, nodes, files, functions, sources: uint32[count] each
    topics: uint32[count], present with FLAG_TOPICS
    robots: uint32[count], present with FLAG_ROBOTS
    levels: uint8[count]
    msgs: u32 byte length, then the messages' UTF-8 joined by NUL (FLAG_NUL_JOINED);
          else uint32[count] byte lengths, u32 byte length, then the bytes

Node, file, function, source, topics and robot strings travel once: each end keeps the same
table (new strings are appended in order; ``FLAG_RESET`` starts a new table), so a
batch carries ids. Text is encoded with ``surrogatepass``: any ``str`` goes through.
"""

from __future__ import annotations

import struct
from array import array
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from itertools import chain, compress
from typing import Any

from .record import LogRecord

FLAG_RESET = 1
FLAG_NUL_JOINED = 2
FLAG_TOPICS = 4
FLAG_ROBOTS = 8
#: Strings one table holds before both ends start a new one (hostile input cannot grow it).
TABLE_LIMIT = 1 << 16
_HEADER = struct.Struct("=III")
_U32 = struct.Struct("=I")


@dataclass(slots=True)
class RecordColumns:
    """Records as columns; every column has one entry per record.

    ``topics`` is ``None`` when no record has any (ROS 1 only has them); ``robots`` is
    ``None`` when no record names its robot (one source, not a fleet).
    """

    stamps: Sequence[int]
    levels: Sequence[int]
    nodes: Sequence[str]
    msgs: Sequence[str]
    files: Sequence[str]
    functions: Sequence[str]
    lines: Sequence[int]
    sources: Sequence[str]
    topics: Sequence[str] | None = None
    robots: Sequence[str] | None = None

    def __len__(self) -> int:
        return len(self.msgs)

    @classmethod
    def from_records(cls, records: Sequence[LogRecord]) -> RecordColumns:
        topics = [r.topics for r in records]
        robots = [r.robot for r in records]
        return cls(
            stamps=[r.stamp_ns for r in records],
            levels=[r.level for r in records],
            nodes=[r.node for r in records],
            msgs=[r.msg for r in records],
            files=[r.file for r in records],
            functions=[r.function for r in records],
            lines=[r.line for r in records],
            sources=[r.source for r in records],
            topics=topics if any(topics) else None,
            robots=robots if any(robots) else None,
        )

    def records(self) -> list[LogRecord]:
        """The same records as ``LogRecord`` objects (seq unset)."""
        records = list(
            map(
                LogRecord,
                self.stamps,
                self.levels,
                self.nodes,
                self.msgs,
                self.files,
                self.functions,
                self.lines,
                self.sources,
            )
        )
        if self.topics is not None:
            for record, topics in zip(records, self.topics, strict=True):
                record.topics = topics
        if self.robots is not None:
            for record, robot in zip(records, self.robots, strict=True):
                record.robot = robot
        return records

    def of_robot(self, robot: str) -> RecordColumns:
        """These records, every one from ``robot`` (one list made at C speed, no step per record)."""
        self.robots = [robot] * len(self) if robot else None
        return self

    @classmethod
    def joined(cls, parts: Sequence[RecordColumns]) -> RecordColumns:
        """The records of ``parts``, one after another, as one batch."""
        if len(parts) == 1:
            return parts[0]
        columns = [list(chain.from_iterable(getattr(part, name) for part in parts)) for name in _COLUMNS]
        return _made(columns, _optional_joined(parts, "topics"), _optional_joined(parts, "robots"))

    @classmethod
    def in_time_order(cls, parts: Sequence[RecordColumns]) -> RecordColumns:
        """The records of ``parts`` as one batch, ordered by stamp (records with one stamp in
        the order given): a fleet's robots' messages, taken in at one time, merged. A batch
        already in order is returned as joined (a C-level comparison, no reordering)."""
        joined = cls.joined(parts)
        order = joined.time_order()
        return joined if order is None else joined.reordered(order)

    def time_order(self) -> list[int] | None:
        """The records' indexes ordered by stamp (one stamp: in the order given); None when
        they are in that order already."""
        order = sorted(range(len(self)), key=self.stamps.__getitem__)
        return None if order == list(range(len(self))) else order

    def reordered(self, order: Sequence[int]) -> RecordColumns:
        """The records at the indexes ``order``, in that order."""
        columns = [list(map(getattr(self, name).__getitem__, order)) for name in _COLUMNS]
        topics, robots = self.topics, self.robots
        return _made(
            columns,
            None if topics is None else list(map(topics.__getitem__, order)),
            None if robots is None else list(map(robots.__getitem__, order)),
        )

    def kept(self, keep: Sequence[bool]) -> RecordColumns:
        """The records whose entry in ``keep`` is true, in order."""
        columns = [list(compress(getattr(self, name), keep)) for name in _COLUMNS]
        topics, robots = self.topics, self.robots
        return _made(
            columns,
            None if topics is None else list(compress(topics, keep)),
            None if robots is None else list(compress(robots, keep)),
        )

    def slice(self, lo: int, hi: int) -> RecordColumns:
        """Records ``lo:hi`` as columns of their own."""
        return RecordColumns(
            self.stamps[lo:hi],
            self.levels[lo:hi],
            self.nodes[lo:hi],
            self.msgs[lo:hi],
            self.files[lo:hi],
            self.functions[lo:hi],
            self.lines[lo:hi],
            self.sources[lo:hi],
            None if self.topics is None else self.topics[lo:hi],
            None if self.robots is None else self.robots[lo:hi],
        )


class ColumnsBuilder:
    """Records gathered column by column as a decoder reads them, made ``RecordColumns`` at the end.

    A decoder appends to ``stamps``, ``levels``, ``nodes``, ``msgs`` and ``tails`` (one
    shared tuple per log statement: ``(file, function, line)``, or with ``topics`` after
    them) and then ``sourced`` gives the records it added their source.
    """

    __slots__ = ("levels", "msgs", "nodes", "sources", "stamps", "tails")

    def __init__(self) -> None:
        self.stamps: list[int] = []
        self.levels: list[int] = []
        self.nodes: list[str] = []
        self.msgs: list[str] = []
        self.tails: list[tuple[Any, ...]] = []
        self.sources: list[str] = []

    def __len__(self) -> int:
        return len(self.msgs)

    def sourced(self, source: str) -> None:
        """The records added since the last call come from ``source``."""
        self.sources += [source] * (len(self.msgs) - len(self.sources))

    def key(self, index: int) -> tuple[int, str, str]:
        """Record ``index``'s ``(stamp, node, msg)``."""
        return self.stamps[index], self.nodes[index], self.msgs[index]

    def cut(self, size: int) -> None:
        """Forget the records from ``size`` on."""
        for column in (self.stamps, self.levels, self.nodes, self.msgs, self.tails, self.sources):
            del column[size:]

    def drop(self, index: int) -> None:
        """Forget record ``index``."""
        for column in (self.stamps, self.levels, self.nodes, self.msgs, self.tails, self.sources):
            del column[index]

    def columns(self) -> RecordColumns:
        """The records as ``RecordColumns`` (``topics`` where the tails have them and one is not empty)."""
        tails = self.tails
        if not tails:
            return RecordColumns([], [], [], [], [], [], [], [])
        files, functions, lines, *more = zip(*tails, strict=True)
        topics = more[0] if more and any(more[0]) else None
        return RecordColumns(
            self.stamps, self.levels, self.nodes, self.msgs, files, functions, lines, self.sources, topics
        )


#: The columns every batch has (``topics`` is optional), in ``RecordColumns``' order.
_COLUMNS = ("stamps", "levels", "nodes", "msgs", "files", "functions", "lines", "sources")


def _made(columns: list[list[Any]], topics: list[str] | None, robots: list[str] | None) -> RecordColumns:
    stamps, levels, nodes, msgs, files, functions, lines, sources = columns
    return RecordColumns(stamps, levels, nodes, msgs, files, functions, lines, sources, topics, robots)


def _optional_joined(parts: Sequence[RecordColumns], name: str) -> list[str] | None:
    """An optional column (``topics``, ``robots``) of ``parts`` joined; None when no part has it."""
    if all(getattr(part, name) is None for part in parts):
        return None
    return list(chain.from_iterable(getattr(part, name) or ("",) * len(part) for part in parts))


class BatchError(ValueError):
    """Packed bytes that are not a batch (cut short, or lengths that do not add up)."""


class BatchPacker:
    """Packs record batches; one per stream (its string table goes with the stream)."""

    def __init__(self, table_limit: int = TABLE_LIMIT) -> None:
        self.table_limit = table_limit
        self._ids: dict[str, int] = {}
        self._reset = True

    def _ids_of(self, texts: Iterable[str], new: list[str]) -> array:
        ids = self._ids
        found = list(map(ids.get, texts))
        try:
            return array("I", found)
        except TypeError:  # a None: strings new to the table (looking for one costs more)
            pass
        texts = list(texts)
        for index, ident in enumerate(found):
            if ident is None:
                text = texts[index]
                ident = ids.get(text)
                if ident is None:
                    ident = ids[text] = len(ids)
                    new.append(text)
                found[index] = ident
        return array("I", found)

    def pack(self, columns: RecordColumns) -> bytes:
        count = len(columns)
        if len(self._ids) + 5 * count > self.table_limit:
            self._ids.clear()
            self._reset = True
        flags = FLAG_RESET if self._reset else 0
        self._reset = False
        new: list[str] = []
        parts: list[bytes] = []
        stamps = array("q", columns.stamps).tobytes()
        lines = array("I", columns.lines).tobytes()
        ids = [self._ids_of(column, new).tobytes() for column in (columns.nodes, columns.files, columns.functions)]
        ids.append(self._ids_of(columns.sources, new).tobytes())
        if columns.topics is not None:
            flags |= FLAG_TOPICS
            ids.append(self._ids_of(columns.topics, new).tobytes())
        if columns.robots is not None:
            flags |= FLAG_ROBOTS
            ids.append(self._ids_of(columns.robots, new).tobytes())
        encoded = [text.encode("utf-8", "surrogatepass") for text in new]
        parts.append(array("I", map(len, encoded)).tobytes())
        parts.extend(encoded)
        parts.append(stamps)
        parts.append(lines)
        parts.extend(ids)
        parts.append(bytes(columns.levels))
        joined = "\0".join(columns.msgs)
        if joined.count("\0") == max(count - 1, 0):
            flags |= FLAG_NUL_JOINED
            blob = joined.encode("utf-8", "surrogatepass")
        else:
            texts = [text.encode("utf-8", "surrogatepass") for text in columns.msgs]
            parts.append(array("I", map(len, texts)).tobytes())
            blob = b"".join(texts)
        parts.append(_U32.pack(len(blob)))
        parts.append(blob)
        return _HEADER.pack(count, flags, len(new)) + b"".join(parts)


class BatchUnpacker:
    """Unpacks what a ``BatchPacker`` packed, in the same order."""

    def __init__(self) -> None:
        self._strings: list[str] = []

    def unpack(self, data: bytes) -> RecordColumns:
        """The batch in ``data``; ``BatchError`` when the bytes do not hold a whole batch."""
        view = memoryview(data)
        try:
            count, flags, new = _HEADER.unpack_from(view, 0)
            pos = _HEADER.size
            lengths = _u32_array(view, pos, new)
            pos += 4 * new
            if flags & FLAG_RESET:
                self._strings = []
            strings = self._strings
            for length in lengths:
                strings.append(_text(view, pos, length))
                pos += length
            stamps = array("q")
            stamps.frombytes(_take(view, pos, 8 * count))
            pos += 8 * count
            lines = _u32_array(view, pos, count)
            pos += 4 * count
            columns: list[list[str]] = []
            for _ in range(4 + bool(flags & FLAG_TOPICS) + bool(flags & FLAG_ROBOTS)):
                ids = _u32_array(view, pos, count)
                pos += 4 * count
                if count and max(ids) >= len(strings):
                    raise BatchError("a string id past the table")
                columns.append(list(map(strings.__getitem__, ids)))
            levels = bytes(_take(view, pos, count))
            pos += count
            if flags & FLAG_NUL_JOINED:
                (size,) = _U32.unpack_from(view, pos)
                msgs = _text(view, pos + 4, size).split("\0") if count else []
                pos += 4 + size
                if len(msgs) != count:
                    raise BatchError("message count does not match")
            else:
                sizes = _u32_array(view, pos, count)
                pos += 4 * count
                (size,) = _U32.unpack_from(view, pos)
                pos += 4
                if sum(sizes) != size:
                    raise BatchError("message lengths do not add up")
                msgs = []
                for length in sizes:
                    msgs.append(_text(view, pos, length))
                    pos += length
        except struct.error:
            raise BatchError("batch cut short") from None
        if pos != len(view):
            raise BatchError(f"{len(view) - pos} bytes left over after the batch")
        return RecordColumns(
            stamps=stamps,
            levels=levels,
            nodes=columns[0],
            msgs=msgs,
            files=columns[1],
            functions=columns[2],
            lines=lines,
            sources=columns[3],
            topics=columns[4] if flags & FLAG_TOPICS else None,
            robots=columns[-1] if flags & FLAG_ROBOTS else None,
        )


def _take(view: memoryview, pos: int, size: int) -> memoryview:
    if pos + size > len(view):
        raise BatchError("batch cut short")
    return view[pos : pos + size]


def _u32_array(view: memoryview, pos: int, count: int) -> array:
    values = array("I")
    values.frombytes(_take(view, pos, 4 * count))
    return values


def _text(view: memoryview, pos: int, size: int) -> str:
    return str(_take(view, pos, size), "utf-8", "surrogatepass")
