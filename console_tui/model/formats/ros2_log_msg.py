"""A direct decoder for serialized ``rcl_interfaces/msg/Log`` messages (CDR), no rclpy needed.

rclpy's ``deserialize_message`` costs several microseconds per Log message; reading the
few fields straight from the bytes costs about one. The layout, after the 4-byte
encapsulation header (alignment counts from its end)::

    int32 stamp.sec, uint32 stamp.nanosec, uint8 level,
    string name, string msg, string file, string function,   # each: uint32 length, bytes
    uint32 line

A string's length counts its terminating NUL and is aligned to 4. Log has no 8-byte
members and no optional or appendable parts, so plain XCDR2 lays it out exactly as
XCDR1; both byte orders are read.

Strings are read as rclpy reads them: up to the first NUL (or the stated length when
there is none), bad UTF-8 as U+FFFD. Node, file and function names repeat in almost
every message: the decoder keeps a bounded cache so records share one ``str`` each.
Malformed input (short buffers, lengths past the end, unknown encapsulations) raises
``CdrError``; nothing in here loops on a length read from the input.
"""

from __future__ import annotations

import struct
from collections.abc import Callable, Iterable
from typing import Any

from ..store.record import LogRecord
from ..store.record_batch import ColumnsBuilder, RecordColumns

#: Encapsulation ids this decoder reads: CDR (XCDR1) and PLAIN_CDR2, big and little endian.
_LITTLE_ENDIAN = {b"\x00\x01", b"\x00\x07"}
_BIG_ENDIAN = {b"\x00\x00", b"\x00\x06"}
#: stamp.sec, stamp.nanosec, level, 3 bytes of padding, the length of ``name``.
_HEAD_LE = struct.Struct("<iIBxxxI").unpack_from
_HEAD_BE = struct.Struct(">iIBxxxI").unpack_from
_U32_LE = struct.Struct("<I").unpack_from
_U32_BE = struct.Struct(">I").unpack_from

INTERN_LIMIT = 4096
INTERN_MAX_BYTES = 256


class CdrError(ValueError):
    """The bytes are not a Log message this decoder can read; the text says why."""


class LogDecoder:
    """Turns serialized Log messages into ``LogRecord``s, sharing repeated strings.

    One decoder per intake thread (it is not thread-safe). The string cache holds at
    most ``intern_limit`` entries of at most ``intern_max_bytes`` bytes each; when full
    it starts over, so hostile input cannot grow it.
    """

    __slots__ = ("_names", "_tails_be", "_tails_le", "intern_limit", "intern_max_bytes")

    def __init__(self, intern_limit: int = INTERN_LIMIT, intern_max_bytes: int = INTERN_MAX_BYTES) -> None:
        #: Names, files and functions by their raw bytes (terminator included).
        self._names: dict[bytes, str] = {}
        #: (file, function, line) by a message's last bytes, one cache per byte order.
        self._tails_le: dict[bytes, tuple[str, str, int]] = {}
        self._tails_be: dict[bytes, tuple[str, str, int]] = {}
        self.intern_limit = intern_limit
        self.intern_max_bytes = intern_max_bytes

    def decode(self, data: bytes, source: str = "") -> LogRecord:
        """The record in ``data`` (bytes-like), with ``source`` as given; ``CdrError`` if unreadable."""
        return self.decode_many((data,), source)[0]

    def decode_many(
        self,
        messages: Iterable[bytes],
        source: str = "",
        refused: Callable[[bytes, CdrError], LogRecord | None] | None = None,
    ) -> list[LogRecord]:
        """``decode_columns``, as ``LogRecord`` objects."""
        return self.decode_columns(messages, source, refused).records()

    def decode_columns(
        self,
        messages: Iterable[bytes],
        source: str = "",
        refused: Callable[[bytes, CdrError], LogRecord | None] | None = None,
    ) -> RecordColumns:
        """The records of many messages, in order, as columns, with ``source`` as given.

        A message the decoder cannot read raises ``CdrError``, or, given ``refused``, is
        handed to ``refused(data, error)``, whose record (if not ``None``) takes its place.
        Written out field by field in one loop, without helper calls and without a
        ``LogRecord`` per message: the intake's hot path.
        """
        batch = ColumnsBuilder()
        # (file, function, line) per message in ``tails``: one shared tuple per log statement.
        stamps, levels, nodes, texts, tails = batch.stamps, batch.levels, batch.nodes, batch.msgs, batch.tails
        names_get = self._names.get
        for data in messages:
            if type(data) is not bytes:
                data = bytes(data)
            size = len(data)
            try:
                encapsulation = data[:2]
                if encapsulation in _LITTLE_ENDIAN:
                    head, u32, cache = _HEAD_LE, _U32_LE, self._tails_le
                elif encapsulation in _BIG_ENDIAN:
                    head, u32, cache = _HEAD_BE, _U32_BE, self._tails_be
                else:
                    raise CdrError(f"not a CDR Log message: encapsulation {encapsulation.hex() or 'missing'}")
                sec, nanosec, level, length = head(data, 4)
                end = 20 + length
                if end > size:
                    raise CdrError(_past_end("name", length, size - 20))
                raw = data[20:end]  # names are cached by their raw bytes, terminator included
                name = names_get(raw)
                if name is None:
                    name = self._intern(raw)
                pos = ((end + 3) & ~3) + 4
                (length,) = u32(data, pos - 4)
                end = pos + length
                if end > size:
                    raise CdrError(_past_end("msg", length, size - pos))
                raw = data[pos : end - 1] if length and not data[end - 1] else data[pos:end]
                if b"\0" in raw:
                    raw = raw[: raw.index(b"\0")]
                msg = raw.decode("utf-8", "replace")
                # file, function and line: the same bytes for every message of one log statement.
                raw = data[(end + 3) & ~3 :]
                tail = cache.get(raw)
                if tail is None:
                    tail = self._read_tail(raw, u32, cache)
            except (CdrError, struct.error) as problem:
                error = problem if isinstance(problem, CdrError) else CdrError(f"Log message truncated: {size} bytes")
                if refused is None:
                    raise error from None
                record = refused(data, error)
                if record is None:
                    continue
                sec, nanosec, level, name, msg = 0, record.stamp_ns, record.level, record.node, record.msg
                tail = (record.file, record.function, record.line)
            stamps.append(sec * 1_000_000_000 + nanosec)
            levels.append(level)
            nodes.append(name)
            texts.append(msg)
            tails.append(tail)
        batch.sourced(source)
        return batch.columns()

    def _read_tail(self, raw: bytes, u32: Any, tails: dict[bytes, tuple[str, str, int]]) -> tuple[str, str, int]:
        """``file``, ``function`` and ``line`` from the end of a message, cached when short."""
        size = len(raw)
        (length,) = u32(raw, 0)
        end = 4 + length
        if end > size:
            raise CdrError(_past_end("file", length, size - 4))
        file = self._intern(raw[4:end])
        pos = ((end + 3) & ~3) + 4
        (length,) = u32(raw, pos - 4)
        end = pos + length
        if end > size:
            raise CdrError(_past_end("function", length, size - pos))
        function = self._intern(raw[pos:end])
        (line,) = u32(raw, (end + 3) & ~3)
        tail = (file, function, line)
        if size <= 2 * self.intern_max_bytes:
            if len(tails) >= self.intern_limit:
                tails.clear()
            tails[raw] = tail
        return tail

    def _intern(self, raw: bytes) -> str:
        """The text of a string's raw bytes (up to the first NUL), shared while cached."""
        names = self._names
        text = names.get(raw)
        if text is None:
            cut = raw.find(0)
            text = (raw if cut < 0 else raw[:cut]).decode("utf-8", "replace")
            if len(raw) <= self.intern_max_bytes:
                if len(names) >= self.intern_limit:
                    names.clear()
                names[raw] = text
        return text


def _past_end(field: str, length: int, left: int) -> str:
    return f"Log message field '{field}' claims {length} bytes, only {max(left, 0)} left"


#: Little-endian CDR; stamp.sec, stamp.nanosec, level and 3 bytes of padding.
_ENCAPSULATION_LE = b"\x00\x01\x00\x00"
_HEAD_PACK = struct.Struct("<iIBxxx").pack
_U32_PACK = struct.Struct("<I").pack
_PADDING = (b"", b"\0\0\0", b"\0\0", b"\0")


class LogEncoder:
    """Turns records back into serialized Log messages (little-endian CDR), as rclpy
    would serialize them, so that they can be published as bytes.

    Names, files and functions repeat: their encoded form is cached (bounded, like the
    decoder's cache). A text with a NUL in it ends there for every reader, as in rclpy.
    """

    __slots__ = ("_cache", "intern_limit")

    def __init__(self, intern_limit: int = INTERN_LIMIT) -> None:
        self._cache: dict[str, bytes] = {}
        self.intern_limit = intern_limit

    def _string(self, text: str) -> bytes:
        """A CDR string (length, bytes, NUL) padded so that what follows is 4-aligned.

        Every string starts 4-aligned here, so its padding depends only on its length."""
        raw = text.encode("utf-8", "replace") + b"\0"
        return _U32_PACK(len(raw)) + raw + _PADDING[len(raw) & 3]

    def _cached(self, text: str) -> bytes:
        found = self._cache.get(text)
        if found is None:
            found = self._string(text)
            if len(text) <= INTERN_MAX_BYTES:
                if len(self._cache) >= self.intern_limit:
                    self._cache.clear()
                self._cache[text] = found
        return found

    def encode(self, record: LogRecord) -> bytes:
        """One record as a serialized ``rcl_interfaces/msg/Log``."""
        sec, nanosec = divmod(record.stamp_ns, 1_000_000_000)
        cached = self._cached
        return b"".join(
            (
                _ENCAPSULATION_LE,
                _HEAD_PACK(sec, nanosec, record.level & 0xFF),
                cached(record.node),
                self._string(record.msg),
                cached(record.file),
                cached(record.function),
                _U32_PACK(record.line & 0xFFFFFFFF),
            )
        )
