"""Storms collapsed: the table's rows with each run of repeats as one row.

A **storm** is a run of one node's consecutive shown messages with the same severity and
the same text (or, with ``mask_digits``, the same text once every run of digits reads
``#``), from the same source and robot (the same message in two files of a run, or from two
robots of a fleet, is no repeat): messages of other nodes in between do not break it, a
message of the same node with another text does. It shows as one row, at its first message,
with its count and the time of its last one; its other messages are no rows while it is
collapsed.
Expanding it (``expand``) makes them rows again where they are, between the others.

``StormRows`` reads like a ``LogView`` (``len``, ``seq_at``, ``row_of``,
``count_before``): the table draws it instead of the view. Its rows are the seqs of the
runs' first messages (and of the messages of expanded storms), in seq order, taken in as
records arrive (``ShownFollower``), so counts are exact at every frame. After a rule change it collapses again from the oldest record in the background;
until it has caught up, the rows it has not reached are the view's own rows. When the
store drops a storm's first message, the next one kept takes its place and the count
goes down by what was dropped.
"""

from __future__ import annotations

import re
from array import array
from bisect import bisect_left
from collections.abc import Sequence
from operator import itemgetter
from typing import NamedTuple

from ..store.find_level import find_node
from ..store.log_store import Chunk, LogStore
from ..store.packed_texts import PackedTexts
from ..view.log_view import LogView
from ..view.shown_rows import ShownPiece, shown_pieces
from .shown_follower import ShownFollower
from .storm_runs import Storm, repeating_nodes, take_apart, take_bulk, take_each

_DIGITS = re.compile(r"[0-9]+")
#: Rows looked through for a collapsed repeat's storm (other nodes' rows in between).
_LOOK_BACK = 200_000


def mask_digits(text: str) -> str:
    """``text`` with every run of digits as ``#``: ``took 12.5 ms`` -> ``took #.# ms``."""
    return _DIGITS.sub("#", text)


class StormBadge(NamedTuple):
    """What a row shows of its storm: ``head`` rows carry the count and the last seq."""

    repeats: int
    first: int
    last: int
    expanded: bool
    head: bool


class StormRows(ShownFollower):
    """The rows of ``view`` with storms collapsed (all of them while ``enabled`` is off)."""

    def __init__(self, store: LogStore, view: LogView, *, mask_digits: bool = False, enabled: bool = True) -> None:
        self._rows = array("q")
        self._start = 0
        #: first seq -> storm, for runs of two messages or more
        self._storms: dict[int, Storm] = {}
        #: node id -> its latest run (which a repeat continues)
        self._runs: dict[int, Storm] = {}
        self._expanded: list[Storm] = []
        #: While the store drops records: the storms whose first message goes, and per node
        #: the one whose repeats are going.
        self._leaving: list[Storm] = []
        self._going: dict[int, Storm] = {}
        self.mask_digits = mask_digits
        super().__init__(store, view)
        self.enabled = enabled

    # -- following the view -----------------------------------------------------------------------

    def reset(self) -> None:
        self._rows = array("q")
        self._start = 0
        self._storms, self._runs, self._expanded = {}, {}, []

    def state(self) -> object:
        return self._rows, self._start, self._storms, self._runs, self._expanded

    def restore(self, state: object) -> None:
        self._rows, self._start, self._storms, self._runs, self._expanded = state  # type: ignore[misc]

    def set_mask_digits(self, mask: bool) -> None:
        if mask != self.mask_digits:
            self.mask_digits = mask
            self._all_shown = None  # counted with the other digits
            self.restart()

    def take(self, piece: ShownPiece) -> None:
        chunk, offsets = piece.chunk, piece.offsets
        msgs: Sequence[str] = chunk.msgs
        mask = mask_digits if self.mask_digits else None
        bulk = not self._expanded and len(offsets) > 1 and chunk.robots is None  # (a fleet's: one by one)
        if bulk:
            repeating = self.chunk_fact(piece, f"repeating nodes {self.mask_digits}", self._repeating_nodes)
            if repeating is not None:
                take_apart(piece, repeating, mask, self._runs, self._storms, self._rows)
                return
        if isinstance(msgs, PackedTexts) and 8 * len(offsets) >= len(msgs):
            msgs = msgs.texts()  # one split, not a slice of the packed text for each
        if bulk:
            take_bulk(piece, msgs, mask, self._runs, self._storms, self._rows)
            return
        if isinstance(offsets, range):
            lo, hi = offsets.start, offsets.stop
            nodes: Sequence[int] = chunk.nodes[lo:hi]
            levels: Sequence[int] = chunk.levels[lo:hi]
            sources: Sequence[int] = chunk.sources[lo:hi]
            texts: Sequence[str] = msgs[lo:hi]
        elif len(offsets) == 1:
            at = offsets[0]
            nodes, levels, sources, texts = [chunk.nodes[at]], [chunk.levels[at]], [chunk.sources[at]], [msgs[at]]
        else:
            pick = itemgetter(*offsets)
            nodes, levels, sources, texts = pick(chunk.nodes), pick(chunk.levels), pick(chunk.sources), pick(msgs)
        if chunk.robots is not None:  # a fleet: one robot's messages never repeat another's
            robots = chunk.robots
            if isinstance(offsets, range):
                picked: Sequence[int] = robots[offsets.start : offsets.stop]
            else:
                picked = [robots[at] for at in offsets]
            sources = [source | robot << 32 for source, robot in zip(sources, picked, strict=False)]
        if mask is not None:
            texts = [mask(text) for text in texts]
        take_each(piece.seqs(), (nodes, levels, sources, texts), self._runs, self._storms, self._rows)

    def _repeating_nodes(self, chunk: Chunk) -> frozenset[int]:
        return repeating_nodes(chunk, mask_digits if self.mask_digits else None)

    def forget(self, piece: ShownPiece) -> None:
        leaving, going, storms, runs = self._leaving, self._going, self._storms, self._runs
        chunk, offsets = piece.chunk, piece.offsets
        if isinstance(offsets, range):
            nodes: Sequence[int] = chunk.nodes[offsets.start : offsets.stop]
        elif len(offsets) == 1:
            nodes = [chunk.nodes[offsets[0]]]
        else:
            nodes = itemgetter(*offsets)(chunk.nodes)
        for seq, node in zip(piece.seqs(), nodes, strict=False):
            storm = storms.get(seq)
            if storm is None:
                run = runs.get(node)
                if run is not None and run.head == seq:
                    storm = run  # the node's latest run, still one message
            if storm is not None:
                storm.count -= 1
                leaving.append(storm)
                going[node] = storm
                continue
            storm = going.get(node)
            if storm is not None and seq <= storm.last:
                storm.count -= 1

    def forgotten(self, new_first: int) -> None:
        """Storms whose first message went start at their next one kept."""
        leaving, self._leaving = self._leaving, []
        self._going.clear()
        for storm in leaving:
            self._storms.pop(storm.head, None)
            if storm.last < new_first or storm.count < 1:
                if self._runs.get(storm.node) is storm:
                    del self._runs[storm.node]
                if storm in self._expanded:
                    self._expanded.remove(storm)
                continue
            head = self._next_of_node(storm.node, new_first, storm.last)
            if head is None:  # cannot happen while counts are right; keep the rows whole
                continue
            storm.head = head
            if storm.count >= 2:
                self._storms[head] = storm
            if storm.expanded:
                members = storm.members
                assert members is not None
                del members[: bisect_left(members, head + 1)]
            else:
                at = bisect_left(self._rows, head, self._start)
                self._rows.insert(at, head)

    def _next_of_node(self, node: int, start: int, last: int) -> int | None:
        """The first shown seq of ``node`` in ``start..last``."""
        view = self.view
        while start <= last:
            seq = find_node(self.store, start, last + 1, node)
            if seq is None:
                return None
            if not view.filtered or view.seq_at(view.row_of(seq)) == seq:
                return seq
            start = seq + 1
        return None

    # -- rows, as a LogView has them --------------------------------------------------------------

    def _fresh(self) -> None:
        self.follow_rules()
        first = self.store.first_seq
        rows = self._rows
        if self._start < len(rows) and rows[self._start] < first:
            self._start = bisect_left(rows, first, self._start)
            if self._start > 4096 and self._start * 2 > len(rows):
                del rows[: self._start]
                self._start = 0

    def _collapsed(self) -> int:
        return len(self._rows) - self._start

    def _raw_from(self) -> int:
        """The view's row of the first record not taken in yet."""
        return self.view.row_of(self.done_to)

    def __len__(self) -> int:
        if not self.enabled:
            return len(self.view)
        self._fresh()
        if self.done_to >= self.store.end_seq:
            return self._collapsed()
        return self._collapsed() + len(self.view) - self._raw_from()

    def seq_at(self, row: int) -> int:
        """The seq shown at ``row``; ``IndexError`` past the end."""
        if not self.enabled:
            return self.view.seq_at(row)
        if row < 0:
            raise IndexError(row)
        self._fresh()
        collapsed = self._collapsed()
        if row < collapsed:
            return self._rows[self._start + row]
        if self.done_to >= self.store.end_seq:
            raise IndexError(row)
        return self.view.seq_at(self._raw_from() + row - collapsed)

    def row_of(self, seq: int) -> int:
        """The row showing ``seq``, or the row of the next one shown after it (a collapsed
        repeat shows in its storm's row, further up)."""
        if not self.enabled:
            return self.view.row_of(seq)
        self._fresh()
        if seq < self.done_to or self.done_to >= self.store.end_seq:
            return bisect_left(self._rows, seq, self._start) - self._start
        return self._collapsed() + self.view.row_of(seq) - self._raw_from()

    def count_before(self, seq: int) -> int:
        return self.row_of(seq)

    def row_showing(self, seq: int) -> int:
        """The row that shows ``seq``: its own, or its storm's when it is a collapsed repeat;
        for a record that is no row (hidden by the rules), the row of the next one shown."""
        row = self.row_of(seq)
        if not self.enabled or seq >= self.done_to or seq not in self.store:
            return row
        if row < len(self) and self.seq_at(row) == seq:
            return row
        view = self.view
        if view.filtered and not (view.row_of(seq) < len(view) and view.seq_at(view.row_of(seq)) == seq):
            return row  # hidden by the rules
        # A collapsed repeat: its storm's row is the nearest row before it of the same node.
        store, node = self.store, self.store.node_id_of(seq)
        for earlier in range(row - 1, max(row - _LOOK_BACK, 0) - 1, -1):
            head = self.seq_at(earlier)
            if store.node_id_of(head) == node:
                storm = self._storms.get(head)
                return earlier if storm is not None and storm.last >= seq else row
        return row

    def row_shown(self, seq: int) -> int | None:
        """The row that shows ``seq`` (its storm's for a collapsed repeat); None when no row
        does (the rules hide it, or it is gone)."""
        row = self.row_showing(seq)
        if not 0 <= row < len(self):
            return None
        return row if self.seq_at(row) <= seq else None  # a row after it: it is no row

    # -- storms -----------------------------------------------------------------------------------

    def storm_of(self, seq: int) -> Storm | None:
        """The storm shown by ``seq``'s row: the storm it starts, or the expanded storm it is part of."""
        if not self.enabled:
            return None
        storm = self._storms.get(seq)
        if storm is not None:
            return storm
        for storm in self._expanded:
            members = storm.members
            if members and storm.head < seq <= storm.last:
                at = bisect_left(members, seq)
                if at < len(members) and members[at] == seq:
                    return storm
        return None

    def badge(self, seq: int) -> StormBadge | None:
        """How ``seq``'s row is marked as a storm, or None for a message on its own."""
        storm = self.storm_of(seq)
        if storm is None:
            return None
        return StormBadge(storm.count, storm.head, storm.last, storm.expanded, storm.head == seq)

    def expand(self, storm: Storm) -> None:
        """Show every message of the storm as a row (each where it is)."""
        if storm.expanded or not self.enabled:
            return
        members = array("q")
        for piece in shown_pieces(self.store, self.view, storm.head + 1, min(storm.last + 1, self.done_to)):
            chunk = piece.chunk
            members.extend(piece.base + offset for offset in piece.offsets if chunk.nodes[offset] == storm.node)
        storm.members = members
        storm.expanded = True
        self._expanded.append(storm)
        self._merge_rows(storm.head, storm.last, members, add=True)

    def collapse(self, storm: Storm) -> None:
        """Show the storm as one row again."""
        if not storm.expanded:
            return
        members = storm.members or array("q")
        storm.expanded = False
        storm.members = None
        if storm in self._expanded:
            self._expanded.remove(storm)
        self._merge_rows(storm.head, storm.last, members, add=False)

    def _merge_rows(self, head: int, last: int, members: array, *, add: bool) -> None:
        rows = self._rows
        lo = bisect_left(rows, head + 1, self._start)
        hi = bisect_left(rows, last + 1, lo)
        if add:
            rows[lo:hi] = array("q", sorted([*rows[lo:hi], *members]))
        else:
            gone = set(members)
            rows[lo:hi] = array("q", [seq for seq in rows[lo:hi] if seq not in gone])

    def collapsed_storms(self) -> list[Storm]:
        """The storms shown as one row each, oldest first."""
        return sorted((storm for storm in self._storms.values() if not storm.expanded), key=lambda storm: storm.head)

    @property
    def storm_count(self) -> int:
        """Storms (runs of two or more) among the rows."""
        return len(self._storms)
