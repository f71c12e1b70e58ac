"""Dropping the ROS 1 log messages that arrive twice.

Two ways a message comes again, with the same ``(stamp, name, text)`` but maybe another
``header.seq`` (the rosout node renumbers it):

- rospy's ``/rosout`` publisher is latched: a new connection to it (the console's first, or
  after a reconnect) starts with the node's last message, which may have come already;
- while the console moves between ``/rosout`` and ``/rosout_agg`` it reads both for a
  moment, so each message of that moment comes once from the node and once from rosout.

So the first message of every new connection is checked against the last one seen from
its node, and while a window is open every message is checked against those of the
window. Outside a window the cost is keeping each batch's last message per node.
"""

from __future__ import annotations

from operator import attrgetter

from ...model.record import LogRecord

#: Keys kept for a window at most (a topic switch opens one for 4 s: 80,000 keys at 20k/s).
WINDOW_KEYS = 200_000
#: Nodes whose last message is kept at most.
NODES_KEPT = 10_000


_node = attrgetter("node")


def _key(record: LogRecord) -> tuple[int, str, str]:
    return (record.stamp_ns, record.node, record.msg)


class Deduplicator:
    """Not thread-safe: one per intake thread."""

    __slots__ = ("_last", "_window", "_window_until", "dropped")

    def __init__(self) -> None:
        #: Each node's last message, to recognise a latched replay.
        self._last: dict[str, LogRecord] = {}
        self._window: set[tuple[int, str, str]] = set()
        self._window_until = 0.0
        #: Messages dropped as repeats so far.
        self.dropped = 0

    def open_window(self, until: float) -> None:
        """Check every message until the monotonic time ``until`` (a later ``until`` extends it)."""
        self._window_until = max(self._window_until, until)

    def is_replay(self, record: LogRecord) -> bool:
        """Whether the first message of a new connection is its node's last message, seen before."""
        last = self._last.get(record.node)
        return last is not None and _key(last) == _key(record)

    def filter(self, records: list[LogRecord], now: float) -> list[LogRecord]:
        """``records`` less those seen before within the window; remembers each node's last one."""
        if now < self._window_until:
            seen = self._window
            kept = []
            for record in records:
                key = _key(record)
                if key in seen:
                    self.dropped += 1
                    continue
                if len(seen) < WINDOW_KEYS:
                    seen.add(key)
                kept.append(record)
            records = kept
        elif self._window:
            self._window = set()
        last = self._last
        if len(last) > NODES_KEPT:
            last.clear()
        last.update(zip(map(_node, records), records, strict=False))
        return records
