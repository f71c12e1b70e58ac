"""ROS 1 bags, through ``rosbags``' index: each log message read at the place the index gives.

A bag whose index is missing (an interrupted recording) or damaged is read record by
record from the start instead (``ros1_bag_scan``), as far as it goes, and a problem says why.
"""

from __future__ import annotations

import heapq
import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from ...model.formats import FormatError
from ...model.store.record import LogRecord
from .log_file import Cancel, describe_error
from .recording_file import ROS1_LOG, RecordingFile, decoder
from .ros1_bag_scan import BagDamaged, BagScan


class Ros1BagFile(RecordingFile):
    kind = "ros1-bag"
    title = "ROS 1 bag"

    def __init__(self, path: Path, source: str) -> None:
        super().__init__(path, source)
        from rosbags.rosbag1 import Reader, ReaderError

        self._reader: Any = Reader(path)
        self._scan: BagScan | None = None
        try:
            self._reader.open()
        except ReaderError as error:
            text = str(error)
            if "encryption" in text or "not supported" in text:
                self.close()
                raise FormatError(f"{path.name}: cannot read this ROS 1 bag: {text}") from None
            if "not indexed" in text:
                text = "the bag has no index (was its recording interrupted? 'rosbag reindex' repairs it)"
            else:
                text = f"its index is damaged ({text})"
            self._read_without_index(text)
            return
        except Exception as error:  # the library's own checks (assertions, struct errors) on a bad index
            self._read_without_index(f"its index is damaged ({describe_error(error)})")
            return
        self._select_log_connections(self._reader.connections)

    def _read_without_index(self, why: str) -> None:
        self.problems.add(f"{why}: read record by record from the start instead, as far as it goes")
        self.close()
        self._scan = BagScan(open(self.path, "rb"), _decompressors())
        self.connections = []
        self.topics = []
        self.unit = "bytes"
        self.total = max(1, os.path.getsize(self.path))

    def close(self) -> None:
        reader, self._reader = getattr(self, "_reader", None), None
        if reader is not None and reader.bio is not None:
            reader.close()
        scan = getattr(self, "_scan", None)
        if scan is not None:
            scan.stream.close()

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        if self._scan is not None:
            yield from self._scanned(self._scan, cancel)
            return
        if not self.connections:
            return
        yield from self._read_then_close(self._messages(), cancel)

    def _scanned(self, scan: BagScan, cancel: Cancel | None) -> Iterator[list[LogRecord]]:
        decode = decoder(ROS1_LOG, "ros1", self.source)

        def items() -> Iterator[tuple[Callable[[bytes], LogRecord], bytes, str]]:
            try:
                for data, where in scan.messages():
                    self.done = scan.position
                    yield decode, data, where
            except BagDamaged as error:
                self.problems.add(f"{error}: what came before it was read", offset=error.offset)
            self.topics = sorted(scan.topics)

        yield from self._read_then_close(items(), cancel, count_messages=False)
        self.done = self.total

    def _messages(self) -> Iterator[tuple[Callable[[bytes], LogRecord], bytes, str]]:
        reader = self._reader
        decode = decoder(ROS1_LOG, "ros1", self.source)
        direct = _ros1_direct_reader(reader, self.connections)
        if direct is None:  # compressed chunks: the library reads them whole
            for number, (_connection, _time, data) in enumerate(reader.messages(connections=self.connections)):
                yield decode, data, f"log message {number + 1}"
            return
        yield from ((decode, data, where) for data, where in direct)


def _decompressors() -> dict[str, Callable[[bytes], bytes]]:
    from rosbags.rosbag1.reader import decompressors

    return dict(decompressors)


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
