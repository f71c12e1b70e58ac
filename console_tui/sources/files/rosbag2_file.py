"""rosbag2 recordings read through ``rosbags``: sqlite3 storage and compressed bags.

A directory is read file by file, each storage file by its own table of topics: the
topics listed in ``metadata.yaml`` are not matched against the files' own (the library
matches them on QoS profiles and type hashes too, and a recording whose metadata differs
there from its files gave no message at all). Message-compressed recordings are
decompressed here; file-compressed ones by the library.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from ...model.formats import FormatError
from ...model.store.record import LogRecord
from .log_file import Cancel, describe_error
from .recording_file import RecordingFile, choose_log_topics, decoder


class Rosbag2File(RecordingFile):
    """A rosbag2 recording read through ``rosbags`` (sqlite3 storage, compressed bags)."""

    kind = "rosbag2"
    title = "rosbag2 recording"

    def __init__(self, path: Path, source: str) -> None:
        super().__init__(path, source)
        from rosbags.rosbag2 import Reader

        if path.suffix == ".db3" or (path.is_dir() and any(path.glob("*.db3"))):
            self.kind, self.title = "sqlite3", "rosbag2 sqlite3"
        try:
            self._reader: Any = Reader(path)
            self._reader.open()
        except Exception as error:
            raise FormatError(f"{path.name}: cannot read this rosbag2 recording: {error}") from None
        storage = self._reader.storage
        #: The storage files, each read with its own topic ids.
        self._storages: list[Any] = list(getattr(storage, "storages", None) or [storage])
        self._decompress = _message_decompressor(self._reader.compression_mode)
        self._select_log_connections([c for part in self._storages for c in part.connections])
        if path.is_dir():
            self._compare_with_metadata(self._reader.connections)

    def _compare_with_metadata(self, listed: list[Any]) -> None:
        """Say so when metadata.yaml promises log messages the files do not hold."""
        promised = {c.topic: c.msgcount for c in listed if c.topic in choose_log_topics([(c.topic, c.msgtype)])}
        held = {c.topic for c in self.connections}
        missing = sorted(topic for topic, count in promised.items() if count and topic not in held)
        if missing:
            self.problems.add(
                f"metadata.yaml lists log messages on {', '.join(missing)}, but the recording's files hold no such topic"
            )

    def close(self) -> None:
        reader, self._reader = getattr(self, "_reader", None), None
        if reader is not None and reader.is_open:
            reader.close()

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        if not self.connections:
            self.close()
            return
        yield from self._read_then_close(self._messages(), cancel)

    def _messages(self) -> Iterator[tuple[Callable[[bytes], LogRecord], bytes, str]]:
        topics = set(self.topics)
        decompress = self._decompress
        for part in self._storages:
            wanted = [c for c in part.connections if c.topic in topics]
            if not wanted:
                continue
            decoders = {c.id: decoder(c.msgtype, c.ext.serialization_format, self.source) for c in wanted}
            for connection, time, data in part.messages(wanted):
                where = f"log message at time {time}"
                if decompress is not None:
                    try:
                        data = decompress(data)
                    except Exception as error:
                        self.problems.add(f"{where}: does not decompress ({describe_error(error)})")
                        continue
                yield decoders[connection.id], data, where


def _message_decompressor(mode: str | None) -> Callable[[bytes], bytes] | None:
    """zstd for recordings compressed message by message, else None."""
    if (mode or "").lower() != "message":
        return None
    try:
        from compression import zstd  # Python 3.14
    except ImportError:
        from backports import zstd  # what rosbags installs before 3.14
    decompress: Callable[[bytes], bytes] = zstd.decompress
    return decompress
