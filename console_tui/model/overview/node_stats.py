"""Counts per node and severity, and each node's rate over the last minute.

``NodeStats`` counts every kept record (whatever the rules hide: it describes the run), a
chunk column at a time, only when asked: ``sync`` counts what arrived since the last call
(for about a budget of time, so that counting a million records does not stall a frame),
``update`` all of it, and the store's eviction hook takes off what the store drops (of what
was counted). Nobody reads the counts while the node panel is closed, so then no record costs
anything here (docs/decisions/0015-node-counts-while-shown.md). The
rate of a node is its records in the last ``window_s`` seconds of stamps (the newest stamp's
second and the ones before it) divided by that window, or by the seconds the history covers
when it is shorter.

In a fleet (records that name their robot) a node is a robot's node: the same name on two
robots is two nodes, each counted on its own (``NodeCounts.robot``).
"""

from __future__ import annotations

from array import array
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from time import perf_counter

from ..levels import MESSAGE_SEVERITIES, severity_bucket
from ..store.find_level import find_level, find_node, severity_range
from ..store.log_store import Chunk, LogStore

NS_PER_S = 1_000_000_000
RATE_WINDOW_S = 60
SLOTS = len(MESSAGE_SEVERITIES)
#: A node's key is its node id, plus its robot's id shifted by this many bits in a fleet.
ROBOT_SHIFT = 32
_SLOT = {level: MESSAGE_SEVERITIES.index(severity_bucket(level)) for level in range(256)}


def _keys(chunk: Chunk, lo: int, hi: int) -> Sequence[int]:
    """The node keys of ``chunk[lo:hi]``: node ids, combined with robot ids in a fleet."""
    nodes = chunk.nodes[lo:hi]
    robots = chunk.robots
    if robots is None:
        return nodes
    return [node | robot << ROBOT_SHIFT for node, robot in zip(nodes, robots[lo:hi], strict=False)]


@dataclass(frozen=True)
class NodeCounts:
    """One node's kept records per severity (DEBUG .. FATAL) and its recent rate."""

    node: str
    node_id: int
    counts: tuple[int, ...]
    rate: float
    #: The robot of a fleet the node runs on, or "".
    robot: str = ""

    @property
    def total(self) -> int:
        return sum(self.counts)

    @property
    def label(self) -> str:
        """The node's name as shown: in a fleet, its robot's first (``picker: /talker``)."""
        return f"{self.robot}: {self.node}" if self.robot else self.node


def robot_counts(nodes: Sequence[NodeCounts]) -> dict[str, tuple[int, ...]]:
    """Each robot's records per severity (DEBUG .. FATAL), from its nodes' counts, by name."""
    totals: dict[str, list[int]] = {}
    for entry in nodes:
        counts = totals.setdefault(entry.robot, [0] * SLOTS)
        for slot, number in enumerate(entry.counts):
            counts[slot] += number
    return {robot: tuple(counts) for robot, counts in sorted(totals.items())}


class NodeStats:
    """Kept records per node and severity over ``store``; call ``sync`` (or ``update``) before
    reading them."""

    def __init__(
        self, store: LogStore, *, window_s: int = RATE_WINDOW_S, clock: Callable[[], float] = perf_counter
    ) -> None:
        self.store = store
        self.window_s = window_s
        self.clock = clock
        #: node key (the node id, and in a fleet the robot id: ``ROBOT_SHIFT``) -> five counts
        #: (DEBUG .. FATAL)
        self._counts: dict[int, list[int]] = {}
        #: second of the stamp -> records of each node key in it (the last ``window_s`` seconds)
        self._seconds: dict[int, Counter[int]] = {}
        self._newest_second: int | None = None
        self._oldest_second: int | None = None
        self._seen_to = store.first_seq
        store.evict_listeners.append(self._evicting)
        store.rewind_listeners.append(self._rewinding)

    def clear(self) -> None:
        """After the store was cleared."""
        self._counts.clear()
        self._seconds.clear()
        self._newest_second = self._oldest_second = None
        self._seen_to = self.store.end_seq

    def update(self) -> None:
        """Count every record not counted yet."""
        self.sync()

    def sync(self, budget_s: float | None = None) -> bool:
        """Count the records not counted yet, a chunk's worth at a time, until about
        ``budget_s`` has gone by (None: all of them); True when every kept record is counted."""
        store = self.store
        start = max(self._seen_to, store.first_seq)
        deadline = None if budget_s is None else self.clock() + budget_s
        for span in store.spans(start, store.end_seq):
            chunk, lo, hi = span.chunk, span.lo, span.hi
            self._count(_keys(chunk, lo, hi), chunk.levels[lo:hi], chunk.stamps[lo:hi], +1)
            self._seen_to = span.seq + hi - lo
            if deadline is not None and self.clock() >= deadline:
                break
        self._seen_to = max(self._seen_to, store.first_seq)
        return self.counted

    @property
    def counted(self) -> bool:
        """Every kept record is counted."""
        return self._seen_to >= self.store.end_seq

    def _evicting(self, first: int, new_first: int) -> None:
        for span in self.store.spans(first, min(new_first, self._seen_to)):
            chunk, lo, hi = span.chunk, span.lo, span.hi
            self._count(_keys(chunk, lo, hi), chunk.levels[lo:hi], chunk.stamps[lo:hi], -1)
        self._oldest_second = None  # found again when asked
        self._seen_to = max(self._seen_to, new_first)

    def _rewinding(self, start: int) -> None:
        """The records from ``start`` on are written again: uncounted, to be counted again."""
        for span in self.store.spans(start, self._seen_to):
            chunk, lo, hi = span.chunk, span.lo, span.hi
            self._count(_keys(chunk, lo, hi), chunk.levels[lo:hi], chunk.stamps[lo:hi], -1)
        self._oldest_second = None
        self._seen_to = min(self._seen_to, max(start, self.store.first_seq))

    def _count(self, nodes: Sequence[int], levels: array, stamps: array, sign: int) -> None:
        counts = self._counts
        slot = _SLOT
        for (node, level), number in Counter(zip(nodes, levels, strict=False)).items():
            node_counts = counts.get(node)
            if node_counts is None:
                node_counts = counts[node] = [0] * SLOTS
            node_counts[slot[level]] += sign * number
        seconds = [stamp // NS_PER_S for stamp in stamps]
        if not seconds:
            return
        newest = max(seconds)
        if sign > 0:
            if self._oldest_second is not None:
                self._oldest_second = min(self._oldest_second, min(seconds))
            if self._newest_second is None or newest > self._newest_second:
                self._newest_second = newest
        cut = (self._newest_second or newest) - self.window_s
        window = self._seconds
        for (second, node), number in Counter(zip(seconds, nodes, strict=False)).items():
            if second > cut:
                window.setdefault(second, Counter())[node] += sign * number
        for second in [second for second in window if second <= cut]:
            del window[second]

    # -- reading ----------------------------------------------------------------------------------

    def window_seconds(self) -> int:
        """The seconds the rates are over: ``window_s``, or less when the history is shorter."""
        if self._newest_second is None:
            return self.window_s
        if self._oldest_second is None:
            oldest = None
            for span in self.store.spans(self.store.first_seq, self.store.end_seq):
                low = min(span.chunk.stamps[span.lo : span.hi]) // NS_PER_S
                oldest = low if oldest is None else min(oldest, low)
                if oldest <= self._newest_second - self.window_s:
                    break
            self._oldest_second = oldest if oldest is not None else self._newest_second
        return max(min(self.window_s, self._newest_second - self._oldest_second + 1), 1)

    def nodes(self) -> list[NodeCounts]:
        """Every node with a kept record, most records first."""
        recent: Counter[int] = Counter()
        for counter in self._seconds.values():
            recent.update(counter)
        seconds = self.window_seconds()
        names, robots, mask = self.store.nodes, self.store.robots, (1 << ROBOT_SHIFT) - 1
        found = [
            NodeCounts(
                names[key & mask],
                key & mask,
                tuple(counts),
                max(recent.get(key, 0), 0) / seconds,
                robots[key >> ROBOT_SHIFT],
            )
            for key, counts in self._counts.items()
            if any(counts)
        ]
        found.sort(key=lambda entry: (-entry.total, entry.robot, entry.node))
        return found

    def busiest(self, number: int = 5) -> list[NodeCounts]:
        """The nodes with the highest rates over the last minute (those with any)."""
        ranked = sorted((entry for entry in self.nodes() if entry.rate > 0), key=lambda e: (-e.rate, e.node))
        return ranked[:number]

    def first_of(self, severity: int) -> int | None:
        """The seq of the first kept record of a severity (levels between steps count under
        the step below), or None."""
        low, high = severity_range(severity)
        return find_level(self.store, self.store.first_seq, self.store.end_seq, low, high)

    def first_of_node(self, node_id: int) -> int | None:
        """The seq of the first kept record of the node (on any robot), or None."""
        return find_node(self.store, self.store.first_seq, self.store.end_seq, node_id)
