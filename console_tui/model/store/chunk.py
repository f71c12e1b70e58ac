"""A chunk of the store: up to ``CHUNK_SIZE`` consecutive records, column by column.

Numbers are ``array``s, the repeated strings (node, file, function, source) ids into the
store's ``StringTable``s, messages ``str``s while the chunk fills and, once it is full, joined
and compressed (``PackedTexts``). ``ChunkSpan`` is a run of a chunk's records, as readers
scan them; ``add_columns`` adds a batch that fits, a column at a time (``extended`` and
``optional_ids``), and ``columns`` gives records back as columns; ``Tables`` are the strings
the chunks name by id.
"""

from __future__ import annotations

from array import array
from collections import Counter
from collections.abc import Iterable, Iterator, Sequence
from typing import Any, NamedTuple

from ..levels import severity_bucket
from .packed_texts import PackedTexts, pack
from .record_batch import RecordColumns

CHUNK_SIZE = 4096


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


class Tables:
    """The strings a store's chunks name by id: nodes, files, functions, sources, topics, robots."""

    __slots__ = ("files", "functions", "nodes", "robots", "sources", "topics")

    def __init__(self) -> None:
        self.nodes = StringTable()
        self.files = StringTable()
        self.functions = StringTable()
        self.sources = StringTable()
        self.topics = StringTable()
        self.topics.id_of("")  # id 0: no topics
        self.robots = StringTable()
        self.robots.id_of("")  # id 0: no robot

    def by_name(self) -> dict[str, StringTable]:
        return {name: getattr(self, name) for name in ("nodes", "files", "functions", "sources", "topics", "robots")}


_BUCKET = {level: int(severity_bucket(level)) for level in range(256)}


class Chunk:
    """Up to ``CHUNK_SIZE`` consecutive records, one array or sequence per field.

    ``lines`` and the id columns are arrays of 2-byte items ("H") or, once a value did
    not fit, 4-byte ones ("I"). ``msgs`` is a list while the chunk fills, then (sealed)
    usually a ``PackedTexts``: read it as a sequence of ``str`` (a slice is a list).
    """

    __slots__ = (
        "files",
        "functions",
        "levels",
        "lines",
        "msgs",
        "nodes",
        "robots",
        "severities",
        "sources",
        "stamps",
        "topics",
    )

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
        #: Its records per severity (as the store's ``counts``), kept as they are added (None: not kept).
        self.severities: dict[int, int] | None = {}

    def __len__(self) -> int:
        return len(self.msgs)

    def add_columns(self, piece: RecordColumns, tables: Tables) -> dict[int, int]:
        """Add ``piece`` (which fits) column by column; its records per severity."""
        levels = piece.levels
        try:
            self.stamps = extended(self.stamps, piece.stamps)
        except (OverflowError, TypeError):
            self.stamps.fromlist([clamp(v, -INT64_MAX, INT64_MAX) for v in piece.stamps])
        try:
            self.levels = extended(self.levels, levels)
        except (OverflowError, TypeError):
            levels = [clamp(v, 0, 255) for v in levels]
            self.levels.fromlist(levels)
        try:
            self.lines = extended(self.lines, piece.lines)
        except (OverflowError, TypeError):
            self.lines = extended(self.lines, [clamp(v, 0, UINT32_MAX) for v in piece.lines])
        self.nodes = extended(self.nodes, tables.nodes.ids_of(piece.nodes))
        self.files = extended(self.files, tables.files.ids_of(piece.files))
        self.functions = extended(self.functions, tables.functions.ids_of(piece.functions))
        self.sources = extended(self.sources, tables.sources.ids_of(piece.sources))
        self.topics = optional_ids(self.topics, len(self.msgs), tables.topics, piece.topics, len(piece))
        self.robots = optional_ids(self.robots, len(self.msgs), tables.robots, piece.robots, len(piece))
        msgs = self.msgs
        assert isinstance(msgs, list), "only the newest chunk grows, and it is never sealed"
        msgs.extend(piece.msgs)
        added: dict[int, int] = {}
        for level, number in Counter(levels).items():
            bucket = _BUCKET[level]
            added[bucket] = added.get(bucket, 0) + number
        kept = self.severities
        if kept is not None:
            for bucket, number in added.items():
                kept[bucket] = kept.get(bucket, 0) + number
        return added

    def columns(self, lo: int, hi: int, tables: Tables) -> RecordColumns:
        """Its records ``lo:hi`` as columns."""

        def strings(table: StringTable, ids: Sequence[int]) -> list[str]:
            return list(map(table.__getitem__, ids))

        return RecordColumns(
            self.stamps[lo:hi].tolist(),
            self.levels[lo:hi].tolist(),
            strings(tables.nodes, self.nodes[lo:hi]),
            list(self.msgs[lo:hi]),
            strings(tables.files, self.files[lo:hi]),
            strings(tables.functions, self.functions[lo:hi]),
            self.lines[lo:hi].tolist(),
            strings(tables.sources, self.sources[lo:hi]),
            None if self.topics is None else strings(tables.topics, self.topics[lo:hi]),
            None if self.robots is None else strings(tables.robots, self.robots[lo:hi]),
        )

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


INT64_MAX = (1 << 63) - 1
UINT32_MAX = 0xFFFFFFFF


def clamp(value: Any, low: int, high: int) -> int:
    return min(max(int(value), low), high)


def extended(column: array, values: Iterable[int]) -> array:
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


def optional_ids(
    column: array | None, before: int, table: StringTable, texts: Sequence[str] | None, count: int
) -> array | None:
    """An optional id column (``topics``, ``robots``) with ``count`` more records' ids: made
    (id 0 for the ``before`` records already in the chunk) when ``texts`` is the first to have any."""
    if texts is not None:
        if column is None:
            column = array("H", bytes(2 * before))
        return extended(column, table.ids_of(texts))
    if column is not None:
        return extended(column, [0] * count)
    return None
