"""ROS 1 bags, through ``rosbags``' index: each log message read at the place the index gives."""

from __future__ import annotations

import heapq
import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from ...model.formats import FormatError
from ...model.record import LogRecord
from .log_file import Cancel
from .recording_file import ROS1_LOG, RecordingFile, decoder


class Ros1BagFile(RecordingFile):
    kind = "ros1-bag"
    title = "ROS 1 bag"

    def __init__(self, path: Path, source: str) -> None:
        super().__init__(path, source)
        from rosbags.rosbag1 import Reader, ReaderError

        self._reader = Reader(path)
        try:
            self._reader.open()
        except ReaderError as error:
            text = str(error)
            if "not indexed" in text:
                text = "the bag has no index (was its recording interrupted?): run 'rosbag reindex' on it"
            raise FormatError(f"{path.name}: cannot read this ROS 1 bag: {text}") from None
        self._select_log_connections(self._reader.connections)

    def close(self) -> None:
        reader, self._reader = getattr(self, "_reader", None), None
        if reader is not None and reader.bio is not None:
            reader.close()

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        if not self.connections:
            return
        try:
            yield from self._decode_all(self._messages(), cancel)
        except Exception as error:
            self.problems.add(f"reading stopped: {error}")
        finally:
            self.close()

    def _messages(self) -> Iterator[tuple[Callable[[bytes], LogRecord], bytes, str]]:
        reader = self._reader
        decode = decoder(ROS1_LOG, "ros1", self.source)
        direct = _ros1_direct_reader(reader, self.connections)
        if direct is None:  # compressed chunks: the library reads them whole
            for number, (_connection, _time, data) in enumerate(reader.messages(connections=self.connections)):
                yield decode, data, f"log message {number + 1}"
            return
        yield from ((decode, data, where) for data, where in direct)


def _ros1_direct_reader(reader: Any, connections: list[Any]) -> Iterator[tuple[bytes, str]] | None:
    """Read each log message at the place the bag's index gives, when every chunk that
    holds one is uncompressed; None when that is not possible."""
    try:
        from rosbags.rosbag1.reader import Header, RecordType, decompressors, read_bytes, read_uint32
    except ImportError:
        return None
    plain = decompressors.get("none")
    indexes = [reader.indexes[c.id] for c in connections]
    if any(reader.chunks[entry.chunk_pos].decompressor is not plain for index in indexes for entry in index):
        return None

    def read() -> Iterator[tuple[bytes, str]]:
        with open(reader.path, "rb", buffering=4096) as bag:
            for entry in heapq.merge(*indexes):
                position = reader.chunks[entry.chunk_pos].datapos + entry.offset
                bag.seek(position)
                while True:
                    header = Header.read(bag)
                    if header.get_uint8("op") != RecordType.CONNECTION:
                        break
                    bag.seek(read_uint32(bag), os.SEEK_CUR)
                if header.get_uint8("op") != RecordType.MSGDATA:
                    raise FormatError(f"byte {position}: the index points at no message")
                yield read_bytes(bag, read_uint32(bag)), f"byte {position}"

    return read()
