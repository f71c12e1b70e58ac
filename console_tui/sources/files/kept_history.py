"""A kept history read again: ``console-tui --history``, the sessions ``--keep-history`` kept.

A kept history is a directory (``console-tui-history`` in the ROS log directory) of session
directories (``kept-<time>-<pid>``), each the segment files its store wrote
(``model/spill_file.py``): runs of records, the strings its chunks name (``TABLES``) and the
chunks themselves (``CHUNK``, ``model/chunk_blob.py``). It is read as one log, oldest session
first, each chunk's records in their order. Chunks of log files read by index hold no
messages (they are in those files): they are left out, and said (open the files again). A
segment cut off (a session killed while writing) gives what came before the cut.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from ...model.store.chunk import Chunk
from ...model.store.chunk_blob import unpack_chunk
from ...model.store.chunk_spill import read_tables
from ...model.store.history_dir import KEPT_PREFIX, kept_sessions
from ...model.store.record import LogRecord
from ...model.store.record_batch import RecordColumns
from ...model.store.spill_file import CHUNK, KEPT, TABLES, records_of, unpack_kept
from ...ros.log_dir import KEPT_HISTORY
from .log_file import Cancel, LogFile


def is_kept_history(path: Path) -> bool:
    """Whether ``path`` is a kept history (``console-tui-history``) or one session's of it."""
    try:
        if path.name == KEPT_HISTORY and path.is_dir():
            return True
        return path.name.startswith(KEPT_PREFIX) and path.is_dir() and any(path.glob("segment-*.ctc"))
    except OSError:
        return False


def _segments(session: Path) -> list[Path]:
    return sorted(session.glob("segment-*.ctc"))


class KeptHistory(LogFile):
    """The records of a kept history (or of one session of it), oldest session first."""

    kind = "history"
    title = "console-tui kept history"

    def __init__(self, path: Path, source: str) -> None:
        super().__init__(path, source)
        self.sessions = [path] if path.name.startswith(KEPT_PREFIX) else kept_sessions(path)
        self.total = max(1, sum(segment.stat().st_size for session in self.sessions for segment in _segments(session)))
        #: Records of log files read by index that were left out.
        self.left_out = 0

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        for session in self.sessions:
            tables: dict[str, list[str]] = {}
            segments = _segments(session)
            last = self._read(segments[-1]) if segments else []
            # The chunks the store held at its end (the rest it had dropped); a session killed before: all.
            kept = next((unpack_kept(blob) for kind, _, blob in reversed(last) if kind == KEPT), None)
            for segment in segments:
                if cancel is not None and cancel.is_set():
                    return
                number = int(segment.stem.rpartition("-")[2])
                for kind, offset, blob in last if segment == segments[-1] else self._read(segment):
                    if kind == TABLES:
                        for name, first, strings in read_tables(blob):
                            table = tables.setdefault(name, [])
                            del table[first:]
                            table.extend(strings)
                    elif kind == CHUNK and (kept is None or (number, offset) in kept):
                        skip = kept[number, offset] if kept is not None else 0
                        batch = self._records(blob, tables, f"{session.name}/{segment.name}")[skip:]
                        if batch:
                            yield batch
                self.done += segment.stat().st_size
        if self.left_out:
            self.problems.add(
                f"{self.left_out:,} records of log files read by index are not in the kept history "
                "(their messages stay in those files): open the files again"
            )
        self.done = self.total

    def _read(self, segment: Path) -> list[tuple[bytes, int, bytes]]:
        try:
            return list(records_of(segment))
        except OSError as error:
            self.problems.add(f"{segment.parent.name}/{segment.name}: cannot read: {error.strerror or error}")
            return []

    def _records(self, blob: bytes, tables: dict[str, list[str]], where: str) -> list[LogRecord]:
        try:
            chunk, file_texts = unpack_chunk(blob)
        except ValueError as error:
            self.problems.add(f"{where}: a damaged chunk left out: {error}")
            return []
        if file_texts is not None:
            self.left_out += len(chunk.levels)
            return []
        try:
            return _columns(chunk, tables).records()
        except IndexError:
            self.problems.add(f"{where}: a chunk names strings its segment does not hold: left out")
            return []


def _columns(chunk: Chunk, tables: dict[str, list[str]]) -> RecordColumns:
    def strings(name: str, column: object) -> list[str]:
        table = tables.get(name, [])
        return [table[ident] for ident in column]  # type: ignore[attr-defined]

    optional = [
        None if getattr(chunk, name) is None else strings(name, getattr(chunk, name)) for name in ("topics", "robots")
    ]
    return RecordColumns(
        chunk.stamps.tolist(),
        chunk.levels.tolist(),
        strings("nodes", chunk.nodes),
        list(chunk.msgs),
        strings("files", chunk.files),
        strings("functions", chunk.functions),
        chunk.lines.tolist(),
        strings("sources", chunk.sources),
        *optional,
    )
