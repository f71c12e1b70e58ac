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

from ...model.store.record_batch import RecordColumns

#: Keys kept for a window at most (a topic switch opens one for 4 s: 80,000 keys at 20k/s).
WINDOW_KEYS = 200_000
#: Nodes whose last message is kept at most.
NODES_KEPT = 10_000

#: What makes two messages one: ``(stamp, node, text)``.
Key = tuple[int, str, str]


class Deduplicator:
    """Not thread-safe: one per intake thread."""

    __slots__ = ("_last", "_window", "_window_until", "dropped")

    def __init__(self) -> None:
        #: Each node's last message, ``(stamp, text)``, to recognise a latched replay.
        self._last: dict[str, tuple[int, str]] = {}
        self._window: set[Key] = set()
        self._window_until = 0.0
        #: Messages dropped as repeats so far.
        self.dropped = 0

    def open_window(self, until: float) -> None:
        """Check every message until the monotonic time ``until`` (a later ``until`` extends it)."""
        self._window_until = max(self._window_until, until)

    def is_replay(self, key: Key) -> bool:
        """Whether the first message of a new connection (its ``(stamp, node, text)``) is its
        node's last message, seen before."""
        stamp, node, text = key
        return self._last.get(node) == (stamp, text)

    def filter(self, batch: RecordColumns, now: float) -> RecordColumns:
        """``batch`` less the records seen before within the window; remembers each node's last one."""
        if now < self._window_until:
            seen = self._window
            keep: list[bool] = []
            for key in zip(batch.stamps, batch.nodes, batch.msgs, strict=True):
                if key in seen:
                    self.dropped += 1
                    keep.append(False)
                    continue
                if len(seen) < WINDOW_KEYS:
                    seen.add(key)
                keep.append(True)
            if not all(keep):
                batch = batch.kept(keep)
        elif self._window:
            self._window = set()
        last = self._last
        if len(last) > NODES_KEPT:
            last.clear()
        last.update(zip(batch.nodes, zip(batch.stamps, batch.msgs, strict=True), strict=True))
        return batch
