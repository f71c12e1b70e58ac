"""rosbag2 MCAP files, with ``mcap``: the log channels' messages found through the chunk indexes.

Where a message index gives a log message's place in an uncompressed chunk, just that
message is read, so a recording full of images costs little more than its log messages.
Compressed chunks that hold log messages are read whole; a file without a usable index
(a cut-off recording) is read from the start as far as it goes.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from ...model.store.record import LogRecord
from .log_file import Cancel
from .recording_file import BATCH, LOG_TYPES, ROS2_LOG, RecordingFile, choose_log_topics, decoder, normalize_type


class McapFile(RecordingFile):
    """A rosbag2 MCAP file (or any MCAP with ROS log channels)."""

    kind = "mcap"
    title = "rosbag2 MCAP"
    unit = "chunks"

    def __init__(self, path: Path, source: str) -> None:
        super().__init__(path, source)
        from mcap.reader import SeekingReader

        self._stream: Any = open(path, "rb")
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
        self.all_topics = sorted({topic for topic, _type in topic_types})
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
