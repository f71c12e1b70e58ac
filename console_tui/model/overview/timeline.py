"""The message rate over the whole history, by severity: what the timeline strip draws.

``Timeline`` counts the rows the table shows (records hidden by the rules are not
counted) in time buckets by their stamps, per severity, and keeps the first seq of each
bucket (where a jump to that time lands). Buckets are ``width_ns`` wide, on a ladder of
widths (1 ms, 10 ms, ..., 1 s, 5 s, 1 min, 5 min, 1 h, 1 day, ...) where each width
divides the next: when the history no longer fits ``MAX_BUCKETS`` buckets, neighbours
merge into the next width up, so the cost of adding a record stays the same however
long the run. ``columns(width)`` groups the buckets into at most ``width`` columns, as
many buckets a column as it takes to fill the width (``TimelineColumns``), for drawing.

It follows the view as records arrive and are dropped (``ShownFollower``): after a rule
change it counts again from the oldest record in the background, and meanwhile
``columns`` shows the counts from before the change.
"""

from __future__ import annotations

from bisect import bisect_left
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from itertools import islice
from operator import itemgetter, le

from ..levels import MESSAGE_SEVERITIES, severity_bucket
from ..store.log_store import Chunk, LogStore
from ..view.log_view import LogView
from ..view.shown_rows import ShownPiece
from .shown_follower import ShownFollower

MS = 1_000_000
S = 1_000 * MS
MIN = 60 * S
H = 60 * MIN
DAY = 24 * H
#: Bucket widths: each divides the next, so buckets merge exactly.
LADDER_NS = (MS, 10 * MS, 100 * MS, S, 5 * S, MIN, 5 * MIN, H, DAY, 10 * DAY, 100 * DAY, 1000 * DAY, 10000 * DAY)
MAX_BUCKETS = 4096
#: Severity slots of a bucket's counts: DEBUG, INFO, WARN, ERROR, FATAL.
SLOTS = len(MESSAGE_SEVERITIES)
_SLOT = {level: MESSAGE_SEVERITIES.index(severity_bucket(level)) for level in range(256)}
_FIRST = SLOTS  # where a bucket keeps its first seq
_NO_SEQ = 1 << 62


@dataclass(frozen=True)
class TimelineColumns:
    """The counts grouped into columns of ``step_ns`` from ``start_ns``, for drawing.

    ``counts[c]`` is the column's five counts (DEBUG .. FATAL); ``first_seqs[c]`` the seq
    of its first shown record (None for an empty column)."""

    start_ns: int
    step_ns: int
    counts: tuple[tuple[int, ...], ...]
    first_seqs: tuple[int | None, ...]
    #: Stamps of the oldest and newest shown records counted.
    oldest_ns: int
    newest_ns: int

    def __len__(self) -> int:
        return len(self.counts)

    def column_of(self, stamp_ns: int) -> int:
        """The column of a stamp, clamped to the columns there are."""
        return min(max((stamp_ns - self.start_ns) // self.step_ns, 0), len(self.counts) - 1)

    def totals(self) -> list[int]:
        return [sum(column) for column in self.counts]

    def peak_rate(self) -> float:
        """The most records a second in any column."""
        return max(self.totals(), default=0) * S / self.step_ns


class _Histogram:
    """Counts per bucket of one width: ``buckets[index] = [5 counts..., first seq]``."""

    __slots__ = ("buckets", "high", "level", "low", "total")

    def __init__(self) -> None:
        self.level = 0
        self.buckets: dict[int, list[int]] = {}
        #: The lowest and highest bucket index there has been (at this width).
        self.low, self.high = 0, -1
        self.total = 0

    @property
    def width_ns(self) -> int:
        return LADDER_NS[self.level]

    def fit(self, oldest_ns: int, newest_ns: int) -> None:
        """Before the first record: start at the width that records stamped ``oldest_ns`` to
        ``newest_ns`` will need (no merging on the way there). Records in that span give it."""
        if self.buckets:
            return
        level, top = 0, len(LADDER_NS) - 1
        while level < top and newest_ns // LADDER_NS[level] - oldest_ns // LADDER_NS[level] >= MAX_BUCKETS:
            level += 1
        self.level = level

    def add(self, piece: ShownPiece, in_order: bool | None) -> None:
        """Count a piece's records; ``in_order``: its chunk's stamps are in order (None: not known)."""
        chunk, offsets = piece.chunk, piece.offsets
        if not offsets:
            return
        stamps = chunk.stamps
        if in_order is None:
            span = stamps[offsets[0] : offsets[-1] + 1]
            in_order = all(map(le, span, islice(span, 1, None)))
        if in_order:
            first, last = stamps[offsets[0]], stamps[offsets[-1]]
        else:
            picked, levels = _columns_of(piece)
            first, last = min(picked), max(picked)
        width = LADDER_NS[self.level]
        low, high = first // width, last // width
        if not self.low <= low <= high <= self.high:
            if self.buckets:
                low, high = min(low, self.low), max(high, self.high)
            if high - low >= MAX_BUCKETS and self.level < len(LADDER_NS) - 1:
                self._widen(low, high)
                width = LADDER_NS[self.level]
                low, high = first // width, last // width
                if self.buckets:
                    low, high = min(low, self.low), max(high, self.high)
            self.low, self.high = low, high
        self.total += len(offsets)
        if in_order:
            self._add_in_order(piece, width)
            return
        buckets = self.buckets
        indexes = [stamp // width for stamp in picked]
        slot = _SLOT
        for (index, level), number in Counter(zip(indexes, levels, strict=False)).items():
            bucket = buckets.get(index)
            if bucket is None:
                bucket = buckets[index] = [0] * SLOTS + [_NO_SEQ]
            bucket[slot[level]] += number
        # The first seq of each bucket: a dict built from the end keeps the first one.
        for index, seq in dict(zip(reversed(indexes), reversed(piece.seqs()), strict=False)).items():
            bucket = buckets[index]
            if seq < bucket[_FIRST]:
                bucket[_FIRST] = seq

    def _add_in_order(self, piece: ShownPiece, width: int) -> None:
        """Stamps in order (as they mostly arrive): each bucket's records are a slice of the
        piece's offsets, found by bisection in the chunk's stamps, then in the offsets."""
        chunk, base, offsets = piece
        buckets, stamps = self.buckets, chunk.stamps
        if isinstance(offsets, range):
            levels = chunk.levels[offsets.start : offsets.stop].tobytes()
        elif len(offsets) > 1:
            levels = bytes(itemgetter(*offsets)(chunk.levels))
        else:
            levels = bytes([chunk.levels[offsets[0]]])
        start, end, top = 0, len(offsets), offsets[-1] + 1
        while start < end:
            at = offsets[start]
            index = stamps[at] // width
            stop = bisect_left(offsets, bisect_left(stamps, (index + 1) * width, at, top), start, end)
            bucket = buckets.get(index)
            if bucket is None:
                bucket = buckets[index] = [0] * SLOTS + [_NO_SEQ]
            _count_levels(bucket, levels[start:stop])
            if base + at < bucket[_FIRST]:
                bucket[_FIRST] = base + at
            start = stop

    def remove(self, stamps: Sequence[int], levels: Sequence[int], new_first: int) -> None:
        width = LADDER_NS[self.level]
        buckets = self.buckets
        slot = _SLOT
        for (index, level), number in Counter(zip((stamp // width for stamp in stamps), levels, strict=False)).items():
            bucket = buckets.get(index)
            if bucket is None:
                continue
            bucket[slot[level]] -= number
            if not any(bucket[:SLOTS]):
                del buckets[index]
            elif bucket[_FIRST] < new_first:
                bucket[_FIRST] = new_first  # its first record goes; the next kept is at or after this
        self.total -= len(stamps)
        # The edges move in to the buckets left: step by step, as the oldest go a few buckets
        # a time (looking for the lowest of thousands for each bucket emptied cost 14 µs a record).
        if not buckets:
            self.low, self.high = 0, -1
            return
        low, high = self.low, self.high
        while low not in buckets:
            low += 1
        while high not in buckets:
            high -= 1
        self.low, self.high = low, high

    def _widen(self, low: int, high: int) -> None:
        """Merge buckets into wider ones until ``low..high`` fits."""
        old = LADDER_NS[self.level]
        level = self.level
        while (
            level < len(LADDER_NS) - 1
            and (high * old // LADDER_NS[level]) - (low * old // LADDER_NS[level]) >= MAX_BUCKETS
        ):
            level += 1
        factor = LADDER_NS[level] // old
        merged: dict[int, list[int]] = {}
        for index, bucket in self.buckets.items():
            into = merged.get(index // factor)
            if into is None:
                merged[index // factor] = list(bucket)
            else:
                for slot in range(SLOTS):
                    into[slot] += bucket[slot]
                into[_FIRST] = min(into[_FIRST], bucket[_FIRST])
        self.buckets = merged
        self.level = level
        if merged:
            self.low, self.high = min(merged), max(merged)

    def columns(self, width: int) -> TimelineColumns | None:
        buckets = self.buckets
        if not buckets or width < 1:
            return None
        bucket_ns = LADDER_NS[self.level]
        low, high = self.low, self.high
        oldest, newest = low * bucket_ns, (high + 1) * bucket_ns
        # As many buckets a column as it takes to fit the width: the strip fills it.
        per_column = -(-(high + 1 - low) // width)
        step = per_column * bucket_ns
        start = oldest
        number = -(-(high + 1 - low) // per_column)
        counts = [[0] * SLOTS for _ in range(number)]
        firsts = [_NO_SEQ] * number
        last = number - 1
        for index, (debug, info, warn, error, fatal, first) in buckets.items():
            column = (index - low) // per_column
            if column > last:
                column = last
            into = counts[column]
            into[0] += debug
            into[1] += info
            into[2] += warn
            into[3] += error
            into[4] += fatal
            if first < firsts[column]:
                firsts[column] = first
        return TimelineColumns(
            start_ns=start,
            step_ns=step,
            counts=tuple(tuple(column) for column in counts),
            first_seqs=tuple(None if seq == _NO_SEQ else seq for seq in firsts),
            oldest_ns=oldest,
            newest_ns=newest,
        )


def _count_levels(bucket: list[int], levels: bytes) -> None:
    """Add records' severities (a byte each) to a bucket's counts: the bytes counted for each
    level there is (cheaper than a ``Counter`` for the few records a narrow bucket holds)."""
    for level in set(levels):
        bucket[_SLOT[level]] += levels.count(level)


def _stamps_in_order(chunk: Chunk) -> bool:
    stamps = chunk.stamps
    return all(map(le, stamps, islice(stamps, 1, None)))


def _columns_of(piece: ShownPiece) -> tuple[Sequence[int], Sequence[int]]:
    """The stamps and levels of a piece's records."""
    chunk, offsets = piece.chunk, piece.offsets
    if isinstance(offsets, range):
        return chunk.stamps[offsets.start : offsets.stop], chunk.levels[offsets.start : offsets.stop]
    if len(offsets) == 1:
        return [chunk.stamps[offsets[0]]], [chunk.levels[offsets[0]]]
    pick = itemgetter(*offsets)
    return pick(chunk.stamps), pick(chunk.levels)


class Timeline(ShownFollower):
    """Shown records per time bucket and severity, over everything kept."""

    def __init__(self, store: LogStore, view: LogView) -> None:
        self._histogram = _Histogram()
        #: What was counted before the rules changed, shown while counting again.
        self._before: _Histogram | None = None
        self.generation = 0
        self._columns_key: tuple | None = None
        self._columns: TimelineColumns | None = None
        super().__init__(store, view)

    @property
    def total(self) -> int:
        """Records counted."""
        return self._histogram.total

    @property
    def bucket_ns(self) -> int:
        return self._histogram.width_ns

    def reset(self) -> None:
        if self._histogram.total and self._before is None:
            self._before = self._histogram
        self._histogram = _Histogram()
        self.generation += 1

    def state(self) -> object:
        return self._histogram

    def restore(self, state: object) -> None:
        assert isinstance(state, _Histogram)
        self._histogram, self._before = state, None
        self.generation += 1

    def take(self, piece: ShownPiece) -> None:
        histogram = self._histogram
        if not histogram.buckets and len(self.view):
            # The width the shown records need, at least: from this first one to the newest.
            store = self.store
            newest = self.view.seq_at(len(self.view) - 1)
            if newest in store:
                stamps = store.stamp_of(piece.base + piece.offsets[0]), store.stamp_of(newest)
                histogram.fit(min(stamps), max(stamps))
        histogram.add(piece, self.chunk_fact(piece, "stamps in order", _stamps_in_order))
        self.generation += 1

    def forget(self, piece: ShownPiece) -> None:
        stamps, levels = _columns_of(piece)
        self._histogram.remove(stamps, levels, _first_after(piece))
        self.generation += 1

    def synced(self) -> None:
        if self._before is not None and not self.rebuilding and not self.view.refiltering:
            self._before = None
            self.generation += 1

    def columns(self, width: int) -> TimelineColumns | None:
        """The counts in at most ``width`` columns (those from before a rule change while
        counting again); None when nothing is counted."""
        histogram = self._before if self._before is not None else self._histogram
        key = (width, self.generation, id(histogram))
        if key != self._columns_key:
            self._columns_key = key
            self._columns = histogram.columns(width)
        return self._columns

    @property
    def recounting(self) -> bool:
        """Counting again after a rule change (``columns`` shows the counts from before)."""
        return self._before is not None


def _first_after(piece: ShownPiece) -> int:
    """The seq after the piece's last record (records before it are going)."""
    return piece.base + piece.offsets[-1] + 1
