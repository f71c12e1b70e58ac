"""ROS 1's logger services on the wire: ``roscpp/GetLoggers`` and ``roscpp/SetLoggerLevel``.

Every roscpp and rospy node offers ``<node>/get_loggers`` and ``<node>/set_logger_level``.
GetLoggers: empty request; response ``uint32 n + (string name, string level)[n]``, levels
as words (roscpp writes them in lower case, rospy in capitals). SetLoggerLevel: request
``string logger, string level``; empty response. A string is a uint32 length and bytes.
"""

from __future__ import annotations

import struct

from ...model.levels import SEVERITY_TABLE, Severity
from ...ros.ros1.tcpros import prefixed, read_prefixed

GET_LOGGERS = "get_loggers"
SET_LOGGER_LEVEL = "set_logger_level"
GET_LOGGERS_MD5 = "32e97e85527d4678a8f9279894bb64b0"
SET_LOGGER_LEVEL_MD5 = "51da076440d78ca1684d36c868df61ea"

#: The words ROS 1 nodes use for each level, by the app's (ROS 2) number.
LEVEL_WORDS = {int(level.severity): level.name for level in SEVERITY_TABLE}
_LEVELS_BY_WORD = {word: level for level, word in LEVEL_WORDS.items()} | {"WARNING": int(Severity.WARN)}
_U32 = struct.Struct("<I")


class ReplyError(ValueError):
    """A service reply that is not what the type says."""


def level_of_word(word: str) -> int | None:
    """The app's level for a ROS 1 level word (any case), None when unknown."""
    return _LEVELS_BY_WORD.get(word.strip().upper())


def decode_loggers(body: bytes) -> list[tuple[str, str]]:
    """A GetLoggers response: ``[(logger name, level word), ...]``."""
    pos = 0

    def text() -> str:
        nonlocal pos
        value, pos = read_prefixed(body, pos, "GetLoggers reply", "name", ReplyError)
        return value.decode("utf-8", "replace")

    if len(body) < 4:
        raise ReplyError("GetLoggers reply cut short")
    (count,) = _U32.unpack_from(body, 0)
    pos = 4
    if count > len(body) // 8:
        raise ReplyError(f"GetLoggers reply claims {count:,} loggers in {len(body)} bytes")
    return [(text(), text()) for _ in range(count)]


def encode_loggers(loggers: list[tuple[str, str]]) -> bytes:
    """A GetLoggers response (what a node sends; for tests)."""
    return _U32.pack(len(loggers)) + b"".join(_string(name) + _string(level) for name, level in loggers)


def encode_set_level(logger: str, word: str) -> bytes:
    """A SetLoggerLevel request."""
    return _string(logger) + _string(word)


def _string(text: str) -> bytes:
    return prefixed(text.encode("utf-8"))
