"""One row for a message that a rosout log, a ROS 2 launch log and its node's own log file hold.

A run's log folder often holds the rosout log (ROS 1's ``rosout.log``, or what ``console-tui
rosout`` wrote) or a ROS 2 launch's ``launch.log`` beside the nodes' own log files (ROS 1's
``<node>-<N>-stdout.log`` and rospy's ``<node>-<N>.log``, ROS 2's rcutils log files):
every message a node logged is in both, its stamps equal or a millisecond or so apart (a
node's file prints its clock to the millisecond or microsecond, and prints it a moment apart
from the stamp it publishes; launch copies the node's console line, stamp and all). Opened
whole, the folder would show each message twice.

``RepeatMerger`` pairs them as a merge by time goes by: records of two of these kinds of log
with the same node (``/talker`` and ``talker`` are one), robot, severity and text, stamps at
most ``TOLERANCE_NS`` apart, are one record, and a third kind's copy joins them. The best
copy is kept: the rosout copy has the message as it was published (its stamp, the file,
function and line the others lack), then the launch log's; its ``source`` names every file
(``rosout.log + talker-2.log``), so the details say where it was read from. Each copy pairs
with one copy of each other kind at most, so a message really logged twice is still two
rows; repeats within one file, or between two files of one kind, are left as they are.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from ...model.store.record import LogRecord

if TYPE_CHECKING:
    from .log_file import LogFile

#: Formats of the rosout logs (``model.formats.rosout_log``: ROS 1's, console-tui rosout's).
ROSOUT_KINDS = frozenset({"rosout", "rosout2"})
#: Formats of the logs of a ROS 2 launch (``model.formats.launch_log``).
LAUNCH_KINDS = frozenset({"launch"})
#: Formats of a node's own log files: ROS 1's console output and rospy log, ROS 2's rcutils log,
#: the journal (rcl_logging_syslog's entries).
NODE_KINDS = frozenset({"ros1-console", "rospy-log", "rcutils", "journal"})
#: The most two copies' stamps may be apart.
TOLERANCE_NS = 20_000_000

#: The kinds of log, the copy kept first.
_ROSOUT, _LAUNCH, _NODE = 0, 1, 2
_SIDES = ((_ROSOUT, ROSOUT_KINDS), (_LAUNCH, LAUNCH_KINDS), (_NODE, NODE_KINDS))


class _Held:
    """A record waiting until no copy of it can come any more (``record`` None: dropped), with
    the kinds of log its copies came from (``sides``)."""

    __slots__ = ("key", "record", "sides")

    def __init__(self, record: LogRecord, sides: frozenset[int], key: tuple | None) -> None:
        self.record: LogRecord | None = record
        self.sides = sides
        self.key = key


class RepeatMerger:
    """Merges the copies of a message in the rosout logs, the launch logs and the node files
    (``merge``); counts them."""

    def __init__(self, tolerance_ns: int = TOLERANCE_NS) -> None:
        self.tolerance_ns = tolerance_ns
        #: Copies merged into another so far.
        self.merged = 0

    def merge(self, batches: Iterable[list[LogRecord]], files: Sequence[LogFile]) -> Iterator[list[LogRecord]]:
        """``batches`` (merged by time) with the copies of each message made one; as they are
        when ``files`` are not of two of the kinds (rosout, launch, node log files)."""
        sides = {file.source: side for file in files for side, kinds in _SIDES if file.kind in kinds}
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
                    held.append(_Held(record, frozenset(), None))
                    continue
                key = (record.node.lstrip("/"), record.robot, record.level, record.msg)
                copies = waiting.get(key)
                if copies is None:
                    copies = waiting[key] = deque()
                pair = next(
                    (h for h in copies if side not in h.sides and abs(h.record.stamp_ns - stamp) <= tolerance),  # type: ignore[union-attr]
                    None,
                )
                if pair is None:
                    entry = _Held(record, frozenset({side}), key)
                    held.append(entry)
                    copies.append(entry)
                    continue
                self.merged += 1
                other = pair.record
                assert other is not None
                sides_now = pair.sides | {side}
                if min(pair.sides) < side:  # the held copy is kept, in its place
                    pair.record = replace(other, source=f"{other.source} + {record.source}")
                    pair.sides = sides_now
                else:  # this copy is kept, in its own place
                    copies.remove(pair)
                    pair.record = None
                    entry = _Held(replace(record, source=f"{record.source} + {other.source}"), sides_now, key)
                    held.append(entry)
                    copies.append(entry)
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
