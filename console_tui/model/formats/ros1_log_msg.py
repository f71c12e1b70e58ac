"""A direct decoder for serialized ROS 1 ``rosgraph_msgs/Log`` messages, no ROS needed.

The layout (ROS 1 serialization: little-endian, no alignment, no encapsulation)::

    uint32 header.seq, uint32 header.stamp.secs, uint32 header.stamp.nsecs,
    string header.frame_id, uint8 level,
    string name, string msg, string file, string function,   # each: uint32 length, bytes
    uint32 line, uint32 n, string topics[n]

Strings carry no terminator and need not be UTF-8: bad bytes read as U+FFFD. Levels are
ROS 1's bits (1, 2, 4, 8, 16), turned into the app's (ROS 2) scale. ``topics`` (the
topics the node publishes) are kept joined by ``,`` as rqt_console shows them.

md5sum acffd30cd6b6de30f120938c17c593fb (what a TCPROS subscriber sends for the type).

One decoder serves the live ROS 1 intake (``decode_frames``: length-prefixed messages as
they come off a TCPROS socket, decoded straight from the receive buffer into columns, the
shape the store keeps) and ROS 1 bags (``decode``). Node names and the
file/function/line/topics tail repeat in almost every message: a bounded cache lets records
share one ``str`` each. Malformed input raises ``Ros1LogError``; nothing here loops on a
length read from the input without checking it against the message's end first.

The live intake may give the decoder a ``frame_loop``: the same loop in C
(``sources/ros1/frame_loop.c``), which reads the frames whose node and tail are cached here
and stops at any other, for this decoder to read that one (``decode_frames``).
"""

from __future__ import annotations

import struct
from collections.abc import Callable, Iterable
from typing import Any

from ..levels import from_ros1
from ..store.record import LogRecord
from ..store.record_batch import ColumnsBuilder

MD5SUM = "acffd30cd6b6de30f120938c17c593fb"
TYPE = "rosgraph_msgs/Log"

#: A frame's length, then the Log's header: seq (skipped), secs, nsecs, len(frame_id).
_FRAME = struct.Struct("<I4xIII").unpack_from
_LEVEL_LENGTH = struct.Struct("<BI").unpack_from  # level, len(name)
_U32 = struct.Struct("<I").unpack_from
_LEVELS = tuple(from_ros1(level) for level in range(256))

INTERN_LIMIT = 4096
INTERN_MAX_BYTES = 512
#: The shortest Log: seq, stamp, four string lengths, level, two more lengths, line, topic count.
MIN_LENGTH = 12 + 4 + 1 + 4 * 4 + 4 + 4
#: Topic lists longer than this are cut (a hostile message cannot make a huge list).
MAX_TOPICS = 1024


class Ros1LogError(ValueError):
    """The bytes are not a ``rosgraph_msgs/Log`` message this decoder can read; the text says why."""


Tail = tuple[str, str, int, str]
#: ``frames(buffer, pos, max_length, names, tails, levels_table, stamps, levels, nodes, msgs,
#: tails_out) -> (pos, stopped)``: see ``sources/ros1/frame_loop.c``.
FrameLoop = Callable[..., tuple[int, bool]]


class Ros1LogDecoder:
    """Turns serialized ``rosgraph_msgs/Log`` messages into records (in columns), sharing repeated strings.

    One decoder per thread (it is not thread-safe). Its caches hold at most
    ``intern_limit`` entries of at most ``intern_max_bytes`` bytes; when full they start
    over, so hostile input cannot grow them.
    """

    __slots__ = ("_names", "_tails", "frame_loop", "intern_limit", "intern_max_bytes")

    def __init__(
        self,
        intern_limit: int = INTERN_LIMIT,
        intern_max_bytes: int = INTERN_MAX_BYTES,
        frame_loop: FrameLoop | None = None,
    ) -> None:
        #: The frame loop in C, or ``None`` (this decoder reads every frame).
        self.frame_loop = frame_loop
        self._names: dict[bytes, str] = {}
        #: (file, function, line, topics) by the bytes from ``file`` to the message's end.
        self._tails: dict[bytes, Tail] = {}
        self.intern_limit = intern_limit
        self.intern_max_bytes = intern_max_bytes

    def decode(self, data: bytes, source: str = "") -> LogRecord:
        """The record in one message's bytes; ``Ros1LogError`` if unreadable."""
        return self._read(bytes(data), 0, len(data), source)

    def decode_many(
        self,
        messages: Iterable[bytes],
        source: str = "",
        refused: Callable[[bytes, Ros1LogError], LogRecord | None] | None = None,
    ) -> list[LogRecord]:
        """Records for many messages, in order; a message the decoder cannot read raises
        ``Ros1LogError``, or, given ``refused``, is handed to ``refused(data, error)``,
        whose record (if not ``None``) takes its place."""
        records: list[LogRecord] = []
        for data in messages:
            data = bytes(data)
            try:
                records.append(self._read(data, 0, len(data), source))
            except Ros1LogError as error:
                if refused is None:
                    raise
                record = refused(data, error)
                if record is not None:
                    records.append(record)
        return records

    def decode_frames(
        self,
        buffer: bytes,
        start: int,
        source: str,
        batch: ColumnsBuilder,
        refused: Callable[[bytes, Ros1LogError], None],
        max_length: int = 1 << 24,
    ) -> int:
        """Decode the whole length-prefixed messages in ``buffer[start:]`` into ``batch``
        (their tails: file, function, line, topics); returns where the first incomplete one
        starts (``len(buffer)`` when none is).

        A message this decoder cannot read goes to ``refused(bytes, error)`` and is skipped.
        A stated length above ``max_length`` raises ``Ros1LogError``: the stream is broken
        (the records added before it are in ``batch``, without their source).
        The hot path of the live ROS 1 intake: the frame loop in C when there is one, else
        written out in one loop, no object per record.
        """
        loop = self.frame_loop
        if loop is None:
            pos = self._frames(buffer, start, batch, refused, max_length, -1)
        else:
            pos = start
            while True:
                pos, stopped = loop(
                    buffer, pos, max_length, self._names, self._tails, _LEVELS,
                    batch.stamps, batch.levels, batch.nodes, batch.msgs, batch.tails,
                )  # fmt: skip
                if not stopped:
                    break
                pos = self._frames(buffer, pos, batch, refused, max_length, 1)
        batch.sourced(source)
        return pos

    def _frames(
        self,
        buffer: bytes,
        pos: int,
        batch: ColumnsBuilder,
        refused: Callable[[bytes, Ros1LogError], None],
        max_length: int,
        count: int,
    ) -> int:
        """``decode_frames`` in Python, for ``count`` frames at most (-1: all there are)."""
        size = len(buffer)
        stamps, levels_of, nodes, msgs, tails = batch.stamps, batch.levels, batch.nodes, batch.msgs, batch.tails
        names_get = self._names.get
        tails_get = self._tails.get
        levels = _LEVELS
        u32 = _U32
        frame = _FRAME
        level_length = _LEVEL_LENGTH
        while count and pos + 4 <= size:
            if pos + 20 <= size:  # the frame's length, then seq (skipped), stamp, len(frame_id)
                length, secs, nsecs, skip = frame(buffer, pos)
            else:
                (length,) = u32(buffer, pos)
                secs = nsecs = skip = 0
            if length > max_length:
                raise Ros1LogError(f"a message of {length:,} bytes announced: not a Log stream")
            begin = pos + 4
            end = begin + length
            if end > size:
                break
            pos = end
            count -= 1
            try:
                if length < MIN_LENGTH:
                    raise Ros1LogError(f"Log message truncated: {length} bytes")
                p = begin + 16 + skip
                if p + 5 > end:
                    raise Ros1LogError(_past_end("header.frame_id", skip, end - begin - 16))
                level, n = level_length(buffer, p)
                p += 5
                q = p + n
                if q + 4 > end:
                    raise Ros1LogError(_past_end("name", n, end - p))
                raw = buffer[p:q]
                name = names_get(raw)
                if name is None:
                    name = self._intern(raw)
                (n,) = u32(buffer, q)
                p = q + 4
                q = p + n
                if q > end:
                    raise Ros1LogError(_past_end("msg", n, end - p))
                msg = buffer[p:q].decode("utf-8", "replace")
                raw = buffer[q:end]
                tail = tails_get(raw)
                if tail is None:
                    tail = self._read_tail(raw)
            except Ros1LogError as error:
                refused(buffer[begin:end], error)
                continue
            stamps.append(secs * 1_000_000_000 + nsecs)
            levels_of.append(levels[level])
            nodes.append(name)
            msgs.append(msg)
            tails.append(tail)
        return pos

    def _read(self, data: bytes, begin: int, end: int, source: str) -> LogRecord:
        batch = ColumnsBuilder()
        problems: list[Ros1LogError] = []
        framed = struct.pack("<I", end - begin) + data[begin:end]
        self.decode_frames(framed, 0, source, batch, lambda _data, error: problems.append(error))
        if problems:
            raise problems[0]
        return batch.columns().records()[0]

    def _read_tail(self, raw: bytes) -> Tail:
        """``file``, ``function``, ``line`` and ``topics`` from the end of a message, cached when short."""
        size = len(raw)
        if size < 4:
            raise Ros1LogError(_past_end("file", 4, size))
        (n,) = _U32(raw, 0)
        p, q = 4, 4 + n
        if q + 4 > size:
            raise Ros1LogError(_past_end("file", n, size - p))
        file = self._intern(raw[p:q])
        (n,) = _U32(raw, q)
        p = q + 4
        q = p + n
        if q + 8 > size:
            raise Ros1LogError(_past_end("function", n, size - p))
        function = self._intern(raw[p:q])
        line, count = struct.unpack_from("<II", raw, q)
        p = q + 8
        if count > (size - p) // 4:
            raise Ros1LogError(f"Log message claims {count:,} topics in {size - p} bytes")
        topics: list[str] = []
        for _ in range(min(count, MAX_TOPICS)):
            if p + 4 > size:
                raise Ros1LogError(_past_end("topics", 4, size - p))
            (n,) = _U32(raw, p)
            p += 4
            q = p + n
            if q > size:
                raise Ros1LogError(_past_end("topics", n, size - p))
            topics.append(raw[p:q].decode("utf-8", "replace"))
            p = q
        tail = (file, function, line, self._intern_text(",".join(topics)))
        if size <= 2 * self.intern_max_bytes:
            if len(self._tails) >= self.intern_limit:
                self._tails.clear()
            self._tails[raw] = tail
        return tail

    def _intern(self, raw: bytes) -> str:
        names = self._names
        text = names.get(raw)
        if text is None:
            text = raw.decode("utf-8", "replace")
            if len(raw) <= self.intern_max_bytes:
                if len(names) >= self.intern_limit:
                    names.clear()
                names[raw] = text
        return text

    def _intern_text(self, text: str) -> str:
        return self._intern(text.encode("utf-8", "surrogatepass")) if text else ""


def encode_log(
    *,
    stamp_ns: int,
    level: int,
    name: str,
    msg: str,
    file: str = "",
    function: str = "",
    line: int = 0,
    topics: Iterable[str] = (),
    seq: int = 0,
    frame_id: str = "",
) -> bytes:
    """One ``rosgraph_msgs/Log`` message serialized (``level`` as ROS 1's bit), no length prefix."""
    secs, nsecs = divmod(stamp_ns, 1_000_000_000)
    parts: list[Any] = [struct.pack("<III", seq, secs, nsecs), _string(frame_id), bytes([level])]
    parts += [_string(name), _string(msg), _string(file), _string(function)]
    topic_list = list(topics)
    parts.append(struct.pack("<II", line, len(topic_list)))
    parts += [_string(topic) for topic in topic_list]
    return b"".join(parts)


def _string(text: str | bytes) -> bytes:
    data = text.encode("utf-8") if isinstance(text, str) else text
    return struct.pack("<I", len(data)) + data


def _past_end(field: str, length: int, left: int) -> str:
    return f"Log message field '{field}' claims {length:,} bytes, only {max(left, 0):,} left"
