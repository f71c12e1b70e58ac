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

``LiveRepeats`` does the same for streams read live (``console-tui run -- ...``: the live
``/rosout``, the launch's terminal, the nodes' output files as they grow), where copies of a
message arrive a moment apart rather than in stamp order: each record waits ``HOLD_NS`` from
its arrival for its copies, in the place of the first copy to come. A copy whose text goes on
with lines the other lacks (a launch joins what a process printed right after a log line to
it) is cut there: the lines after are a record of their own. A copy may name no node
(roslaunch prints a node's console line without its name): it pairs with a copy of any node,
whose name the record keeps.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Iterator, Sequence
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
#: Live: how long a record waits after it arrived for its copies from the other streams
#: (the nodes' output files are looked at every 0.25 s and hold lines up to 0.5 s).
HOLD_NS = 1_000_000_000

#: The kinds of log, the copy kept first: the rosout copy, the launch's, the node's own.
SIDE_ROSOUT, SIDE_LAUNCH, SIDE_NODE = 0, 1, 2
_SIDES = ((SIDE_ROSOUT, ROSOUT_KINDS), (SIDE_LAUNCH, LAUNCH_KINDS), (SIDE_NODE, NODE_KINDS))


class _Held:
    """A record waiting until no copy of it can come any more (``record`` None: dropped), with
    the kinds of log its copies came from (``sides``) and when it arrived (live)."""

    __slots__ = ("arrived", "key", "record", "sides")

    def __init__(self, record: LogRecord, sides: frozenset[int], key: tuple | None, arrived: int = 0) -> None:
        self.record: LogRecord | None = record
        self.sides = sides
        self.key = key
        self.arrived = arrived


class _Pairs:
    """The records held while their copies may come, and the pairing of copies: by node
    (files), or with a copy that names no node pairing with any node's (``any_node``)."""

    def __init__(
        self, counts: RepeatMerger, *, any_node: bool = False, rest_node: Callable[[LogRecord], str] | None = None
    ) -> None:
        self.counts = counts
        self.any_node = any_node
        self.rest_node = rest_node
        self.held: deque[_Held] = deque()
        self.waiting: dict[tuple, deque[_Held]] = {}

    def add(self, record: LogRecord, side: int | None, arrived: int = 0) -> None:
        held = self.held
        if side is None:
            held.append(_Held(record, frozenset(), None, arrived))
            return
        node = record.node.lstrip("/")
        any_node = self.any_node
        # Live, the first line keys: a launch's copy may have lines the process printed after it.
        key = (
            (record.robot, record.level, record.msg.split("\n", 1)[0])
            if any_node
            else (node, record.robot, record.level, record.msg)
        )
        copies = self.waiting.get(key)
        if copies is None:
            copies = self.waiting[key] = deque()
        stamp, tolerance, msg = record.stamp_ns, self.counts.tolerance_ns, record.msg
        pair = next(
            (
                h
                for h in copies
                if side not in h.sides
                and abs(h.record.stamp_ns - stamp) <= tolerance  # type: ignore[union-attr]
                and (not any_node or (_same_node(h.record.node, node) and _same_text(h.record.msg, msg)))  # type: ignore[union-attr]
            ),
            None,
        )
        if pair is None:
            entry = _Held(record, frozenset({side}), key, arrived)
            held.append(entry)
            copies.append(entry)
            return
        self.counts.merged += 1
        other = pair.record
        assert other is not None
        if len(other.msg) != len(msg):  # one copy goes on with lines the other lacks: those, a record of their own
            if len(msg) > len(other.msg):
                record, rest = _cut(record, len(other.msg))
                rest_side = side
            else:
                other, rest = _cut(other, len(msg))
                pair.record, rest_side = other, min(pair.sides)
            if self.rest_node is not None:
                rest.node = self.rest_node(rest)
            self.add(rest, rest_side, arrived)
        sides_now = pair.sides | {side}
        if min(pair.sides) < side or any_node:  # the held copy keeps its place (live: the first to come)
            pair.record = _kept(other, record) if min(pair.sides) < side else _kept(record, other)
            pair.sides = sides_now
        else:  # this copy is kept, in its own place
            copies.remove(pair)
            pair.record = None
            entry = _Held(_kept(record, other), sides_now, key, arrived)
            held.append(entry)
            copies.append(entry)

    def due(self, *, stamp_before: int | None = None, arrived_before: int | None = None) -> list[LogRecord]:
        """The held records, in order, up to the first one stamped at ``stamp_before`` or later
        (or arrived at ``arrived_before`` or later); every one when both are None."""
        out: list[LogRecord] = []
        held, waiting = self.held, self.waiting
        while held:
            entry = held[0]
            record = entry.record
            if record is not None:
                if stamp_before is not None and record.stamp_ns >= stamp_before:
                    break
                if arrived_before is not None and entry.arrived >= arrived_before:
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


def _same_node(held: str, node: str) -> bool:
    """Whether two copies' nodes may be one: equal, or one of them unnamed."""
    held = held.lstrip("/")
    return held == node or not held or not node


def _same_text(held: str, msg: str) -> bool:
    """Whether two copies' texts are one message: equal, or one its first lines of the other."""
    return held == msg or held.startswith(msg + "\n") or msg.startswith(held + "\n")


def _cut(record: LogRecord, length: int) -> tuple[LogRecord, LogRecord]:
    """A record's text up to ``length``, and the lines after it as a record of their own."""
    return replace(record, msg=record.msg[:length]), replace(record, msg=record.msg[length + 1 :])


def _kept(kept: LogRecord, other: LogRecord) -> LogRecord:
    """The copy kept, naming both sources (and the other's node when it names none)."""
    return replace(kept, source=f"{kept.source} + {other.source}", node=kept.node or other.node)


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
        pairs = _Pairs(self)
        newest = None
        for batch in batches:
            for record in batch:
                stamp = record.stamp_ns
                newest = stamp if newest is None else max(newest, stamp)
                pairs.add(record, sides.get(record.source))
            out = pairs.due(stamp_before=None if newest is None else newest - self.tolerance_ns)
            if out:
                yield out
        out = pairs.due()
        if out:
            yield out


class LiveRepeats:
    """The copies of a message that arrive from several live streams made one: ``add`` each
    stream's records with its kind (``SIDE_ROSOUT``, ``SIDE_LAUNCH``, ``SIDE_NODE``) and the
    time they arrived; ``due`` gives those that waited ``hold_ns``; ``merged`` counts."""

    def __init__(
        self,
        hold_ns: int = HOLD_NS,
        tolerance_ns: int = TOLERANCE_NS,
        *,
        rest_node: Callable[[LogRecord], str] | None = None,
    ) -> None:
        self.hold_ns = hold_ns
        self.counts = RepeatMerger(tolerance_ns)
        #: The node of the lines cut off a copy (by default the copy's).
        self._pairs = _Pairs(self.counts, any_node=True, rest_node=rest_node)

    @property
    def merged(self) -> int:
        return self.counts.merged

    def add(self, records: Iterable[LogRecord], side: int, now_ns: int) -> None:
        for record in records:
            self._pairs.add(record, side, now_ns)

    def due(self, now_ns: int) -> list[LogRecord]:
        return self._pairs.due(arrived_before=now_ns - self.hold_ns + 1)

    def flush(self) -> list[LogRecord]:
        """Every record held (the streams have ended)."""
        return self._pairs.due()
