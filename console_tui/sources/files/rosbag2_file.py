"""rosbag2 recordings read through ``rosbags``: sqlite3 storage and compressed bags."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from ...model.formats import FormatError
from ...model.record import LogRecord
from .log_file import Cancel
from .recording_file import RecordingFile, decoder


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
            self._reader = Reader(path)
            self._reader.open()
        except Exception as error:
            raise FormatError(f"{path.name}: cannot read this rosbag2 recording: {error}") from None
        self._select_log_connections(self._reader.connections)

    def close(self) -> None:
        reader, self._reader = getattr(self, "_reader", None), None
        if reader is not None and reader.is_open:
            reader.close()

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        if not self.connections:
            self.close()
            return
        decoders = {c.id: decoder(c.msgtype, c.ext.serialization_format, self.source) for c in self.connections}
        messages = (
            (decoders[connection.id], data, f"log message at time {time}")
            for connection, time, data in self._reader.messages(connections=self.connections)
        )
        try:
            yield from self._decode_all(messages, cancel)
        except Exception as error:
            self.problems.add(f"reading stopped: {type(error).__name__}: {error}")
        finally:
            self.close()
