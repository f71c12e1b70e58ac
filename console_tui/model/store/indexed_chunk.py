"""A log file read by its index: each chunk's columns kept, its messages read from the file when read.

A file indexed (``sources/files/file_index.py``) comes to the store as ``IndexedChunk``s: the
columns of 4,096 records (stamps, levels, nodes, ...) and where their lines are in the file,
not their messages. The store writes the columns to disk as any full chunk's
(``LogStore.extend_indexed``), naming the file's bytes instead of the messages; a chunk read
back is a ``FileChunk``, whose messages its ``TextSource`` reads from the file the first time
they are read. So a file of tens of millions of lines costs its index, not its text.

A column of strings comes as ids into a list of the file's own (``IdColumn``): the store maps
them to its tables' ids, once for each string.
"""

from __future__ import annotations

from array import array
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from typing import Protocol

from .chunk import Chunk
from .chunk_blob import FileTexts
from .packed_texts import PackedTexts
from .record_batch import RecordColumns


class TextSource(Protocol):
    """What reads a file's messages again: those of the bytes ``texts.start:end``, checked
    against the records' ``stamps`` (a file that changed gives placeholders that say so, and
    its ``problem``)."""

    #: Why some messages could not be read again (the file changed), or "".
    problem: str

    def load(self, texts: FileTexts, stamps: array) -> list[str] | PackedTexts: ...

    def holds(self, texts: FileTexts, needle: bytes, lower: bool) -> bool | None:
        """Whether the file's bytes ``texts.start:end`` hold ``needle`` (lower-cased ASCII when
        ``lower``), or None when that cannot be told."""
        ...


@dataclass(slots=True)
class IdColumn:
    """A column of strings: ``ids`` into ``names`` (None: every record's is ``names[0]``)."""

    ids: array | None
    names: Sequence[str]

    def strings(self, count: int) -> list[str]:
        if self.ids is None:
            return [self.names[0]] * count
        names = self.names
        return [names[ident] for ident in self.ids]


@dataclass(slots=True)
class IndexedChunk:
    """Up to ``CHUNK_SIZE`` records of a log file without their messages: bytes ``start:end``
    of the file ``source`` reads again."""

    stamps: array
    levels: array
    nodes: IdColumn
    files: IdColumn
    functions: IdColumn
    sources: IdColumn
    #: Line numbers (None: none, all 0).
    lines: array | None
    start: int
    end: int
    source: TextSource
    #: ROS 1's topics, a fleet's robots (None: no record has any).
    topics: IdColumn | None = None
    robots: IdColumn | None = None
    #: Each message is its bytes in the file as they are (``FileTexts.verbatim``).
    verbatim: bool = False

    def __len__(self) -> int:
        return len(self.levels)

    def with_messages(self) -> RecordColumns:
        """The records whole, their messages read from the file now (what a store without a
        disk keeps)."""
        count = len(self)
        texts = self.source.load(FileTexts(-1, self.verbatim, self.start, self.end), self.stamps)
        return RecordColumns(
            self.stamps.tolist(),
            self.levels.tolist(),
            self.nodes.strings(count),
            list(texts),
            self.files.strings(count),
            self.functions.strings(count),
            self.lines.tolist() if self.lines is not None else [0] * count,
            self.sources.strings(count),
            self.topics.strings(count) if self.topics is not None else None,
            self.robots.strings(count) if self.robots is not None else None,
        )


class FileChunk(Chunk):
    """A chunk whose messages are read from their file the first time they are read."""

    __slots__ = ("_held", "_load", "_texts", "file_texts", "text_source")
    _load: Callable[[], list[str] | PackedTexts]
    _texts: list[str] | PackedTexts | None
    _held: dict[tuple[str, bool], bool]
    #: Where its messages are, and what reads them.
    file_texts: FileTexts
    text_source: TextSource

    @classmethod
    def of(cls, chunk: Chunk, source: TextSource, texts: FileTexts) -> FileChunk:
        made = cls.__new__(cls)
        for name in (
            "stamps",
            "levels",
            "lines",
            "nodes",
            "files",
            "functions",
            "sources",
            "topics",
            "robots",
            "severities",
        ):
            setattr(made, name, getattr(chunk, name))
        made._load, made._texts = partial(source.load, texts, made.stamps), None
        made.file_texts, made.text_source = texts, source
        made._held = {}
        return made

    def may_hold(self, text: str, lower: bool) -> bool:
        """Whether a message of the chunk may hold ``text`` (lower-cased ASCII when ``lower``),
        as its bytes in the file say without reading its messages (True when they cannot tell)."""
        if not self.file_texts.verbatim or self._texts is not None:
            return True
        key = (text, lower)
        held = self._held.get(key)
        if held is None:
            found = self.text_source.holds(self.file_texts, text.encode("utf-8"), lower)
            held = self._held[key] = found is not False
        return held

    @property
    def msgs(self) -> list[str] | PackedTexts:
        texts = self._texts
        if texts is None:
            texts = self._texts = self._load()
        return texts

    @msgs.setter
    def msgs(self, texts: list[str] | PackedTexts) -> None:
        self._texts = texts

    def __len__(self) -> int:
        return len(self.levels)
