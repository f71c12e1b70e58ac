"""Log messages from recordings: rosbag2 (MCAP, sqlite3) and ROS 1 bags.

Only the log topics are read (``rcl_interfaces/msg/Log``, ``rosgraph_msgs/Log``), found
through each recording's index; no other topic's messages are decoded. Where the
index gives a log message's exact place in an uncompressed chunk (ROS 1 bags, MCAP
with message indexes), just that message is read, so a recording full of images costs
little more than its log messages. Compressed chunks that hold log messages are read
whole (decompression needs the whole chunk). The libraries: ``rosbags`` (ROS 1 index,
rosbag2 directories and sqlite3, message decoding) and ``mcap`` (MCAP summary and
records) -- the ``files`` extra.
"""

from __future__ import annotations

import heapq
import os
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

from ...model.formats import FormatError
from ...model.formats.ros1_log_msg import Ros1LogDecoder
from ...model.formats.ros2_log_msg import LogDecoder
from ...model.record import LogRecord
from ..log_topics import ROSOUT, ROSOUT_AGG
from .log_file import Cancel, LogFile

ROS2_LOG = "rcl_interfaces/msg/Log"
ROS1_LOG = "rosgraph_msgs/msg/Log"
LOG_TYPES = frozenset({ROS2_LOG, ROS1_LOG})
BATCH = 5_000
MISSING_EXTRA = "reading recordings needs the 'files' extra: pip install 'console-tui[files]' (rosbags, mcap)"


def normalize_type(name: str) -> str:
    """``rosgraph_msgs/Log`` -> ``rosgraph_msgs/msg/Log``; other names unchanged."""
    parts = name.split("/")
    return f"{parts[0]}/msg/{parts[1]}" if len(parts) == 2 else name


def choose_log_topics(topic_types: Iterable[tuple[str, str]]) -> set[str]:
    """The topics to read: every log-typed topic, less ``/rosout`` when ``/rosout_agg``
    (which repeats all of it) was recorded too."""
    topics = {topic for topic, msgtype in topic_types if normalize_type(msgtype) in LOG_TYPES}
    if ROSOUT_AGG in topics:
        topics.discard(ROSOUT)
    return topics


def decoder(msgtype: str, encoding: str, source: str) -> Callable[[bytes], LogRecord]:
    """A function from a serialized log message (CDR or ROS 1) to a record: the live
    intakes' direct decoders, one reading of each layout."""
    msgtype = normalize_type(msgtype)
    if encoding == "ros1" or (msgtype == ROS1_LOG and encoding != "cdr"):
        decode_ros1 = Ros1LogDecoder().decode

        def decode_ros1_log(data: bytes) -> LogRecord:
            return decode_ros1(data, source)

        return decode_ros1_log
    decode = LogDecoder().decode

    def decode_cdr(data: bytes) -> LogRecord:
        return decode(bytes(data), source)

    return decode_cdr


class _RecordingFile(LogFile):
    """What the recording readers share: decoding with problems noted, batching."""

    unit = "messages"

    def _select_log_connections(self, connections: list[Any]) -> None:
        """Keep the log connections of a rosbags reader; progress counts their messages."""
        topics = choose_log_topics((c.topic, c.msgtype) for c in connections)
        self.connections = [c for c in connections if c.topic in topics]
        self.topics = sorted(topics)
        self.total = max(1, sum(c.msgcount for c in self.connections))

    def _decode_all(
        self,
        items: Iterable[tuple[Callable[[bytes], LogRecord], bytes, str]],
        cancel: Cancel | None,
        *,
        count_messages: bool = True,
    ) -> Iterator[list[LogRecord]]:
        """Decode ``(decode, data, where)`` items into batches; a message that cannot be
        decoded becomes a problem (``where`` says which). Counts messages as progress
        unless the caller counts something else."""
        batch: list[LogRecord] = []
        for decode, data, where in items:
            if count_messages:
                self.done += 1
            try:
                batch.append(decode(data))
            except Exception as error:  # corrupt data must not end the load
                self.problems.add(f"{where}: cannot decode the log message ({type(error).__name__}: {error})")
            if len(batch) >= BATCH:
                yield batch
                batch = []
                if cancel is not None and cancel.is_set():
                    return
        if batch:
            yield batch


# -- ROS 1 bags ------------------------------------------------------------------------------


class Ros1BagFile(_RecordingFile):
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


# -- MCAP ---------------------------------------------------------------------------------------


class McapFile(_RecordingFile):
    """A rosbag2 MCAP file (or any MCAP with ROS log channels)."""

    kind = "mcap"
    title = "rosbag2 MCAP"
    unit = "chunks"

    def __init__(self, path: Path, source: str) -> None:
        super().__init__(path, source)
        from mcap.reader import SeekingReader

        self._stream = open(path, "rb")
        self.summary: Any = None
        try:
            self.summary = SeekingReader(self._stream).get_summary()
        except Exception as error:  # no footer or summary: a cut-off recording
            self.problems.add(
                f"no usable index ({type(error).__name__}: {error}); reading the whole file instead "
                "(was the recording cut off?)"
            )
        if self.summary is None or not self.summary.chunk_indexes:
            self._index = None
            self.unit = "bytes"
            self.total = max(1, os.path.getsize(path))
            self.topics: list[str] = []
            return
        channels = self.summary.channels
        schemas = self.summary.schemas
        topic_types = [
            (ch.topic, schemas[ch.schema_id].name if ch.schema_id in schemas else "") for ch in channels.values()
        ]
        topics = choose_log_topics(topic_types)
        self.topics = sorted(topics)
        self._decoders = {
            channel_id: decoder(schemas[ch.schema_id].name, ch.message_encoding, source)
            for channel_id, ch in channels.items()
            if ch.topic in topics and ch.schema_id in schemas
        }
        self._index = [
            chunk
            for chunk in sorted(self.summary.chunk_indexes, key=lambda c: (c.message_start_time, c.chunk_start_offset))
            if not chunk.message_index_offsets or any(ch in self._decoders for ch in chunk.message_index_offsets)
        ]
        self.total = max(1, len(self._index))

    def close(self) -> None:
        stream, self._stream = getattr(self, "_stream", None), None
        if stream is not None:
            stream.close()

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        try:
            if self._index is None:
                yield from self._scan(cancel)
            elif self._decoders:
                yield from self._decode_all(self._indexed_messages(), cancel, count_messages=False)
        finally:
            self.close()

    def _indexed_messages(self) -> Iterator[tuple[Callable[[bytes], LogRecord], bytes, str]]:
        from mcap.data_stream import ReadDataStream
        from mcap.records import Chunk, Message, MessageIndex
        from mcap.stream_reader import breakup_chunk

        stream = self._stream
        data = ReadDataStream(stream)
        wanted = self._decoders
        for number, chunk in enumerate(self._index or ()):
            messages: list[Any] = []
            offsets = {ch: pos for ch, pos in chunk.message_index_offsets.items() if ch in wanted}
            try:
                if chunk.compression == "" and offsets:
                    records_start = chunk.chunk_start_offset + 1 + 8 + 8 + 8 + 8 + 4 + 4 + len(chunk.compression) + 8
                    for position in offsets.values():
                        stream.seek(position + 1 + 8)
                        for _time, offset in MessageIndex.read(data).records:
                            stream.seek(records_start + offset)
                            opcode, length = data.read1(), data.read8()
                            if opcode != 0x05:
                                raise ValueError(f"byte {records_start + offset}: the index points at no message")
                            messages.append(Message.read(data, length))
                else:
                    stream.seek(chunk.chunk_start_offset + 1 + 8)
                    records = breakup_chunk(Chunk.read(data))
                    messages = [r for r in records if isinstance(r, Message) and r.channel_id in wanted]
            except Exception as error:
                self.problems.add(
                    f"chunk at byte {chunk.chunk_start_offset} unreadable ({type(error).__name__}: {error})",
                    offset=chunk.chunk_start_offset,
                )
                messages = []
            messages.sort(key=lambda m: m.log_time)
            for message in messages:
                yield wanted[message.channel_id], message.data, f"chunk at byte {chunk.chunk_start_offset}"
            self.done = number + 1

    def _scan(self, cancel: Cancel | None) -> Iterator[list[LogRecord]]:
        """No index: read the file from the start, as far as it goes."""
        from mcap.records import Channel, Message, Schema
        from mcap.stream_reader import StreamReader

        stream = self._stream
        stream.seek(0)
        schemas: dict[int, str] = {}
        decoders: dict[int, Callable[[bytes], LogRecord] | None] = {}
        batch: list[LogRecord] = []
        topics: set[str] = set()
        try:
            for record in StreamReader(stream, record_size_limit=1 << 31).records:
                if isinstance(record, Schema):
                    schemas[record.id] = record.name
                elif isinstance(record, Channel):
                    msgtype = schemas.get(record.schema_id, "")
                    is_log = normalize_type(msgtype) in LOG_TYPES
                    decoders[record.id] = decoder(msgtype, record.message_encoding, self.source) if is_log else None
                    if is_log:
                        topics.add(record.topic)
                elif isinstance(record, Message):
                    decode = decoders.get(record.channel_id)
                    if decode is None:
                        continue
                    try:
                        batch.append(decode(record.data))
                    except Exception as error:
                        self.problems.add(f"cannot decode a log message ({error})", offset=stream.tell())
                    if len(batch) >= BATCH:
                        self.done = stream.tell()
                        yield batch
                        batch = []
                        if cancel is not None and cancel.is_set():
                            return
        except Exception as error:
            self.problems.add(
                f"the recording ends early or is damaged here ({type(error).__name__}: {error}); "
                "what came before was read",
                offset=stream.tell(),
            )
        self.topics = sorted(choose_log_topics((t, ROS2_LOG) for t in topics))
        if batch:
            yield batch
        self.done = self.total


# -- rosbag2 directories and sqlite3, through rosbags -----------------------------------------


class Rosbag2File(_RecordingFile):
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


class ChainedFile(LogFile):
    """Several files read one after another as one (the files of a split rosbag2 recording)."""

    def __init__(self, path: Path, source: str, parts: list[LogFile], kind: str, title: str) -> None:
        super().__init__(path, source)
        self.parts = parts
        self.kind, self.title, self.unit = kind, title, "files"
        self.total = len(parts)
        self.topics = sorted({t for p in parts for t in getattr(p, "topics", [])})
        for part in parts:
            part.problems = self.problems

    @property
    def fraction(self) -> float:
        return (self.done + (self.parts[self.done].fraction if self.done < len(self.parts) else 0)) / self.total

    def batches(self, cancel: Cancel | None = None) -> Iterator[list[LogRecord]]:
        for part in self.parts:
            yield from part.batches(cancel)
            self.done += 1
            if cancel is not None and cancel.is_set():
                return

    def close(self) -> None:
        for part in self.parts:
            part.close()


def open_recording(path: Path, source: str, kind: str) -> LogFile:
    """Open a recording of ``kind`` (``ros1-bag``, ``mcap``, ``sqlite3``, ``rosbag2`` for a
    directory). Raises ``FormatError`` with a message for the user."""
    try:
        import mcap  # noqa: F401
        import rosbags  # noqa: F401
    except ImportError:
        raise FormatError(f"{path.name}: {MISSING_EXTRA}") from None
    if kind == "ros1-bag":
        return Ros1BagFile(path, source)
    if kind == "mcap":
        return McapFile(path, source)
    if kind == "sqlite3":
        if path.suffix != ".db3":
            raise FormatError(f"{path.name}: an SQLite database, but not a rosbag2 .db3 file")
        return Rosbag2File(path, source)
    if kind == "rosbag2":
        return _open_rosbag2_directory(path, source)
    raise FormatError(f"{path.name}: unknown recording kind {kind!r}")


def _open_rosbag2_directory(path: Path, source: str) -> LogFile:
    """A rosbag2 directory: plain MCAP files are read with the index-guided reader,
    anything else (sqlite3, compressed) through rosbags."""
    metadata_path = path / "metadata.yaml"
    if not metadata_path.exists():
        mcaps = sorted(path.glob("*.mcap"))
        if len(mcaps) == 1:
            return McapFile(mcaps[0], source)
        raise FormatError(f"{path.name}: a directory, but not a rosbag2 recording (no metadata.yaml)")
    from ruamel.yaml import YAML

    try:
        info = YAML(typ="safe").load(metadata_path.read_text())["rosbag2_bagfile_information"]
        storage = info.get("storage_identifier", "")
        compressed = (info.get("compression_mode") or "").lower() not in ("", "none")
        files = [path / Path(name).name for name in info.get("relative_file_paths", [])]
    except Exception as error:
        raise FormatError(f"{path.name}: its metadata.yaml is unreadable: {error}") from None
    if storage == "mcap" and not compressed and files and all(f.exists() for f in files):
        parts: list[LogFile] = [McapFile(f, source) for f in files]
        return parts[0] if len(parts) == 1 else ChainedFile(path, source, parts, "mcap", "rosbag2 MCAP")
    return Rosbag2File(path, source)
