"""One row for a message that both a rosout log and its node's own log file hold.

A run's log folder often holds the rosout log (ROS 1's ``rosout.log``, or what ``console-tui
rosout`` wrote) beside the nodes' own log files (ROS 1's ``<node>-<N>-stdout.log`` and
rospy's ``<node>-<N>.log``, ROS 2's rcutils log files): every message a node logged is in
both, its stamps a millisecond or so apart (a node's file prints its clock to the
millisecond or microsecond, and prints it a moment apart from the stamp it publishes).
Opened whole, the folder would show each message twice.

``RepeatMerger`` pairs them as a merge by time goes by: a record of a rosout log and one of
a node's own log file with the same node (``/talker`` and ``talker`` are one), robot,
severity and text, stamps at most ``TOLERANCE_NS`` apart, are one record. The rosout copy is
kept: it has the message as it was published (its stamp, the file, function and line the
node's file lacks); its ``source`` names both files (``rosout.log + talker-2.log``), so the
details say where it was read from. Each copy pairs with one copy at most, so a message
really logged twice is still two rows; repeats within one file, or between two node files,
or two rosout logs, are left as they are.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from ...model.record import LogRecord

if TYPE_CHECKING:
    from .log_file import LogFile

#: Formats of the rosout logs (``model.formats.rosout_log``: ROS 1's, console-tui rosout's).
ROSOUT_KINDS = frozenset({"rosout", "rosout2"})
#: Formats of a node's own log files: ROS 1's console output and rospy log, ROS 2's rcutils log.
NODE_KINDS = frozenset({"ros1-console", "rospy-log", "rcutils"})
#: The most a rosout copy's stamp and its node file's copy's may be apart.
TOLERANCE_NS = 20_000_000

_ROSOUT, _NODE = 0, 1


class _Held:
    """A record waiting until no copy of it can come any more (``record`` None: dropped)."""

    __slots__ = ("key", "record", "side")

    def __init__(self, record: LogRecord, side: int | None, key: tuple | None) -> None:
        self.record: LogRecord | None = record
        self.side = side
        self.key = key


class RepeatMerger:
    """Merges the rosout logs' copies with the node files' copies (``merge``); counts them."""

    def __init__(self, tolerance_ns: int = TOLERANCE_NS) -> None:
        self.tolerance_ns = tolerance_ns
        #: Pairs made one record so far.
        self.merged = 0

    def merge(self, batches: Iterable[list[LogRecord]], files: Sequence[LogFile]) -> Iterator[list[LogRecord]]:
        """``batches`` (merged by time) with each pair made one; as they are when ``files``
        are not a rosout log and node log files both."""
        sides = {file.source: _ROSOUT for file in files if file.kind in ROSOUT_KINDS}
        sides.update({file.source: _NODE for file in files if file.kind in NODE_KINDS})
        if len(set(sides.values())) < 2:
            return iter(batches)
        return self._merged(batches, sides)

    def _merged(self, batches: Iterable[list[LogRecord]], sides: dict[str, int]) -> Iterator[list[LogRecord]]:
        held: deque[_Held] = deque()
        waiting: dict[tuple, deque[_Held]] = {}
        newest = None
        tolerance = self.tolerance_ns
        for batch in batches:
            for record in batch:
                side = sides.get(record.source)
                stamp = record.stamp_ns
                newest = stamp if newest is None else max(newest, stamp)
                if side is None:
                    held.append(_Held(record, None, None))
                    continue
                key = (record.node.lstrip("/"), record.robot, record.level, record.msg)
                copies = waiting.get(key)
                pair = None
                if copies:
                    pair = next(
                        (h for h in copies if h.side != side and abs(h.record.stamp_ns - stamp) <= tolerance),  # type: ignore[union-attr]
                        None,
                    )
                if pair is None:
                    entry = _Held(record, side, key)
                    held.append(entry)
                    waiting.setdefault(key, deque()).append(entry)
                    continue
                copies.remove(pair)  # type: ignore[union-attr]  # found in it
                self.merged += 1
                other = pair.record
                assert other is not None
                rosout, node = (other, record) if pair.side == _ROSOUT else (record, other)
                kept = replace(rosout, source=f"{rosout.source} + {node.source}")
                if pair.side == _ROSOUT:
                    pair.record, pair.key = kept, None
                else:
                    pair.record = None  # the node's copy goes; the rosout copy comes in its own place
                    held.append(_Held(kept, None, None))
            out = self._due(held, waiting, None if newest is None else newest - tolerance)
            if out:
                yield out
        out = self._due(held, waiting, None)
        if out:
            yield out

    @staticmethod
    def _due(held: deque[_Held], waiting: dict[tuple, deque[_Held]], before: int | None) -> list[LogRecord]:
        """The held records older than ``before`` (None: all), in order, let go."""
        out: list[LogRecord] = []
        while held:
            entry = held[0]
            record = entry.record
            if record is not None and before is not None and record.stamp_ns >= before:
                break
            held.popleft()
            if record is None:
                continue
            out.append(record)
            key = entry.key
            if key is not None:
                copies = waiting[key]
                if copies[0] is entry:
                    copies.popleft()
                else:
                    copies.remove(entry)
                if not copies:
                    del waiting[key]
        return out
