"""A ROS 1 bag read without its index: record by record from the start, as far as it goes.

For bags whose index is missing (an interrupted recording, ``.bag.active``) or damaged.
A bag (v2.0) is the line ``#ROSBAG V2.0``, then records, each a uint32 header length, the
header (fields, each a uint32 length and ``name=value``), a uint32 data length and the
data. Chunk records (op 5) hold connection records (op 7: ``conn``, ``topic``; the data's
fields give the ``type``) and message data records (op 2: ``conn``, ``time``; the data is
the message), compressed as the chunk's ``compression`` field says. Index records (op 4),
chunk infos (op 6) and the bag header (op 3) are passed over.
"""

from __future__ import annotations

import io
import struct
from collections.abc import Callable, Iterator
from typing import BinaryIO

from ..log_topics import ROSOUT, ROSOUT_AGG
from .recording_file import ROS1_LOG, normalize_type

OP_MSGDATA, OP_CHUNK, OP_CONNECTION = 2, 5, 7
MAGIC = b"#ROSBAG V2.0\n"
#: A header longer than this is damage, not a header.
_MAX_HEADER = 1 << 20
_UINT32 = struct.Struct("<I")


class BagDamaged(Exception):
    """The bag cannot be read on from ``offset``."""

    def __init__(self, offset: int, what: str) -> None:
        super().__init__(what)
        self.offset = offset


def header_fields(data: bytes) -> dict[str, bytes]:
    """``name=value`` fields, each a uint32 length and the field."""
    fields: dict[str, bytes] = {}
    position = 0
    while position + 4 <= len(data):
        (length,) = _UINT32.unpack_from(data, position)
        field = data[position + 4 : position + 4 + length]
        position += 4 + length
        name, sep, value = field.partition(b"=")
        if sep:
            fields[name.decode("ascii", "replace")] = value
    return fields


def _records(stream: BinaryIO, base: int) -> Iterator[tuple[int, dict[str, bytes], int]]:
    """``(offset, header, data length)`` of each record; the stream is left at its data."""
    while True:
        offset = base + stream.tell()
        head = stream.read(4)
        if not head:
            return
        if len(head) < 4:
            raise BagDamaged(offset, "the bag ends inside a record")
        (length,) = _UINT32.unpack(head)
        if length > _MAX_HEADER:
            raise BagDamaged(offset, f"a record header of {length:,} bytes (damaged data)")
        header = stream.read(length)
        size = stream.read(4)
        if len(header) < length or len(size) < 4:
            raise BagDamaged(offset, "the bag ends inside a record")
        yield offset, header_fields(header), _UINT32.unpack(size)[0]


def _read(stream: BinaryIO, size: int, offset: int) -> bytes:
    data = stream.read(size)
    if len(data) < size:
        raise BagDamaged(offset, "the bag ends inside a record")
    return data


class BagScan:
    """The log messages of a bag, in the order they were written.

    ``messages()`` yields ``(data, where)`` for every ``rosgraph_msgs/Log`` message;
    ``position`` is how far the file has been read (for progress); ``topics`` the log
    topics met so far. When ``/rosout_agg`` shows up, ``/rosout`` (which it repeats) is
    read no further.
    """

    def __init__(self, stream: BinaryIO, decompressors: dict[str, Callable[[bytes], bytes]]) -> None:
        self.stream = stream
        self.decompressors = decompressors
        self.position = 0
        self.topics: set[str] = set()
        self._log_connections: dict[int, str] = {}

    def messages(self) -> Iterator[tuple[bytes, str]]:
        """Raises ``BagDamaged`` where the file cannot be read on."""
        stream = self.stream
        stream.seek(0)
        if stream.read(len(MAGIC)) != MAGIC:
            raise BagDamaged(0, "not a ROS 1 bag of version 2.0")
        for offset, header, size in _records(stream, 0):
            op = header.get("op", b"\xff")[:1]
            if op == bytes([OP_CHUNK]):
                compression = header.get("compression", b"none").decode("ascii", "replace")
                if compression == "none":  # a chunk cut short still holds the messages before the cut
                    data = stream.read(size)
                    yield from self._chunk(io.BytesIO(data), offset)
                    if len(data) < size:
                        raise BagDamaged(offset, "the bag ends inside this chunk")
                    self.position = stream.tell()
                    continue
                decompress = self.decompressors.get(compression)
                if decompress is None:
                    raise BagDamaged(
                        offset, f"a chunk compressed with {compression!r}, which this reader does not know"
                    )
                try:
                    data = decompress(_read(stream, size, offset))
                except BagDamaged:
                    raise
                except Exception as error:
                    raise BagDamaged(offset, f"a chunk that does not decompress ({type(error).__name__})") from None
                yield from self._chunk(io.BytesIO(data), offset)
            elif op == bytes([OP_CONNECTION]):
                self._connection(header, _read(stream, size, offset))
            elif op == bytes([OP_MSGDATA]):
                data = _read(stream, size, offset)
                if self._is_log(header):
                    yield data, f"byte {offset}"
            else:
                stream.seek(size, io.SEEK_CUR)
            self.position = stream.tell()

    def _chunk(self, chunk: io.BytesIO, chunk_offset: int) -> Iterator[tuple[bytes, str]]:
        try:
            for offset, header, size in _records(chunk, 0):
                op = header.get("op", b"\xff")[:1]
                data = _read(chunk, size, offset)
                if op == bytes([OP_CONNECTION]):
                    self._connection(header, data)
                elif op == bytes([OP_MSGDATA]) and self._is_log(header):
                    yield data, f"chunk at byte {chunk_offset}"
        except BagDamaged as error:
            raise BagDamaged(chunk_offset, f"a damaged chunk ({error})") from None

    def _connection(self, header: dict[str, bytes], data: bytes) -> None:
        conn = header.get("conn", b"")
        msgtype = header_fields(data).get("type", b"").decode("utf-8", "replace")
        if len(conn) != 4 or normalize_type(msgtype) != ROS1_LOG:
            return
        topic = header.get("topic", b"").decode("utf-8", "replace")
        self._log_connections[_UINT32.unpack(conn)[0]] = topic
        self.topics.add(topic)

    def _is_log(self, header: dict[str, bytes]) -> bool:
        conn = header.get("conn", b"")
        if len(conn) != 4:
            return False
        topic = self._log_connections.get(_UINT32.unpack(conn)[0])
        return topic is not None and not (topic == ROSOUT and ROSOUT_AGG in self.topics)
