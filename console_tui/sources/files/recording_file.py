"""What the recording readers share: which topics hold log messages, decoding them, batching.

Only the log topics are read (``rcl_interfaces/msg/Log``, ``rosgraph_msgs/Log``), found
through each recording's index; no other topic's messages are decoded. The libraries:
``rosbags`` (ROS 1 index, rosbag2 directories and sqlite3) and ``mcap``
(MCAP summary and records) -- the ``files`` extra.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from typing import Any

from ...model.formats.ros1_log_msg import Ros1LogDecoder
from ...model.formats.ros2_log_msg import LogDecoder
from ...model.store.record import LogRecord
from ..log_topics import ROSOUT, ROSOUT_AGG
from .log_file import Cancel, LogFile, reading_stopped

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


class RecordingFile(LogFile):
    """What the recording readers share: decoding with problems noted, batching."""

    unit = "messages"
    #: The log topics read, and every topic the recording holds (when known).
    topics: list[str]
    all_topics: list[str]

    def _select_log_connections(self, connections: list[Any]) -> None:
        """Keep the log connections of a rosbags reader; progress counts their messages."""
        topics = choose_log_topics((c.topic, c.msgtype) for c in connections)
        self.connections = [c for c in connections if c.topic in topics]
        self.topics = sorted(topics)
        self.all_topics = sorted({c.topic for c in connections})
        self.total = max(1, sum(c.msgcount for c in self.connections))

    def empty_reason(self) -> str:
        topics = getattr(self, "topics", [])
        if topics:
            return f"no log messages: its log topics ({', '.join(topics)}) hold none"
        others = getattr(self, "all_topics", [])
        if not others:
            return "no log messages: the recording holds no topics"
        shown = ", ".join(others[:8]) + (f" and {len(others) - 8} more" if len(others) > 8 else "")
        return f"no log messages: no log topic (rcl_interfaces/msg/Log, rosgraph_msgs/Log) was recorded, only {shown}"

    def _read_then_close(
        self,
        items: Iterable[tuple[Callable[[bytes], LogRecord], bytes, str]],
        cancel: Cancel | None,
        *,
        count_messages: bool = True,
    ) -> Iterator[list[LogRecord]]:
        """``_decode_all``, where an error the library did not expect ends the reading (and
        a problem says so); the file is closed either way."""
        try:
            yield from self._decode_all(items, cancel, count_messages=count_messages)
        except Exception as error:
            self.problems.add(reading_stopped(error))
        finally:
            self.close()

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
