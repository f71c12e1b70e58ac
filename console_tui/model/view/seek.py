"""Finding the next row of some kind (an error, a warning, a search match) in a million.

A ``Hits`` function answers for a span of a chunk which records it picks (their offsets,
ascending). A ``Walk`` goes over the kept records from a seq, newer or older, a span at a
time; a ``Seeker`` walks until it finds a record that is picked *and* shown under the
view's rules, in steps of a time budget, so a caller on the event loop never waits long:
the jump to an error a million rows away is a few steps.

``Hits`` functions that run users' regexes are called under ``time_limit`` (a catastrophic
pattern is abandoned with ``MatchTimeout``, as the rules are).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import compress

from ..levels import severity_bucket
from ..rules.time_limit import MatchTimeout, time_limit
from ..store.log_store import CHUNK_SIZE, Chunk, ChunkSpan, LogStore
from .log_view import LogView

#: ``hits(chunk, lo, hi)``: the offsets in ``lo..hi`` of the records picked, ascending.
Hits = Callable[[Chunk, int, int], Sequence[int]]

#: Longest one call of a ``Hits`` function may take (a regex past it is abandoned).
HITS_LIMIT_S = 0.25
_MIN_PIECE, _START_PIECE = 64, 1024


def view_shows(view: LogView, seq: int) -> bool:
    """Whether the view shows ``seq`` as a row (under its rules)."""
    store = view.store
    if seq not in store:
        return False
    if not view.filtered:
        return True
    row = view.row_of(seq)
    return row < len(view) and view.seq_at(row) == seq


def level_hits(at_least: int) -> Hits:
    """Records of severity ``at_least`` or worse (levels between steps count under the step below)."""
    table = bytes(1 if severity_bucket(level) >= at_least else 0 for level in range(256))

    def hits(chunk: Chunk, lo: int, hi: int) -> Sequence[int]:
        return list(compress(range(lo, hi), chunk.levels[lo:hi].tobytes().translate(table)))

    return hits


class Walk:
    """Spans of kept records from ``start``: ``start`` and newer (``forward``), or older than
    ``start`` newest first. ``at`` is where it goes on from; records evicted meanwhile are
    skipped, records that arrive meanwhile are walked too (forward)."""

    def __init__(self, store: LogStore, start: int, forward: bool) -> None:
        self.store = store
        self.forward = forward
        self.at = min(max(start, store.first_seq), store.end_seq)

    @property
    def done(self) -> bool:
        store = self.store
        return self.at >= store.end_seq if self.forward else self.at <= store.first_seq

    def next_span(self, rows: int) -> ChunkSpan | None:
        """The next span, of at most ``rows`` records and inside one chunk; None when done."""
        store = self.store
        if self.forward:
            start = max(self.at, store.first_seq)
            stop = min(start + rows, store.end_seq, (start // CHUNK_SIZE + 1) * CHUNK_SIZE)
            span = next(store.spans(start, stop), None)
            self.at = stop if span is not None else max(self.at, store.end_seq)
        else:
            stop = min(self.at, store.end_seq)
            start = max(stop - rows, store.first_seq, ((stop - 1) // CHUNK_SIZE) * CHUNK_SIZE)
            span = next(store.spans(start, stop), None)
            self.at = start if span is not None else min(self.at, store.first_seq)
        return span


class PieceSize:
    """Records per piece, sized so that a piece takes about a quarter of the budget."""

    def __init__(self) -> None:
        self.rows = _START_PIECE

    def learn(self, rows: int, seconds: float, budget_s: float) -> None:
        if rows:
            per_row = max(seconds, 1e-9) / rows
            self.rows = min(max(int(budget_s / 4 / per_row), _MIN_PIECE), CHUNK_SIZE)


class Seeker:
    """The nearest record from ``start`` (``start`` itself when ``inclusive``) that ``hits``
    picks and the view shows, found in steps. ``found`` is its seq once ``step`` says done,
    or None when there is none. ``failed`` says why, when ``hits`` was too slow."""

    def __init__(
        self,
        view: LogView,
        hits: Hits,
        start: int,
        *,
        forward: bool,
        inclusive: bool = False,
        limit: int | None = None,
    ) -> None:
        self.view = view
        self.hits = hits
        self.forward = forward
        # Forward walks ``begin`` and newer, backward what is older than ``begin``.
        begin = start + 1 if forward != inclusive else start
        self.walk = Walk(view.store, begin, forward)
        #: Rows at or past this seq are not looked at (a paused table's end).
        self.limit = limit
        self.found: int | None = None
        self.failed = ""
        self.finished = False
        self._piece = PieceSize()

    def step(self, budget_s: float = 0.008) -> bool:
        """Look on for about ``budget_s``; True when done (found, or nothing left)."""
        if self.finished:
            return True
        clock = self.view.clock  # the view's: tests inject one
        deadline = clock() + budget_s
        while True:
            span = self.walk.next_span(self._piece.rows)
            if span is None or (self.forward and self.limit is not None and span.seq >= self.limit):
                self.finished = True
                return True
            began = clock()
            try:
                with time_limit(HITS_LIMIT_S):
                    offsets = self.hits(span.chunk, span.lo, span.hi)
            except MatchTimeout:
                self.failed = f"too slow: testing {span.hi - span.lo:,} messages took over {HITS_LIMIT_S:g} s"
                self.finished = True
                return True
            now = clock()
            self._piece.learn(span.hi - span.lo, now - began, budget_s)
            base = span.seq - span.lo
            for offset in offsets if self.forward else reversed(offsets):
                seq = base + offset
                if self.limit is not None and seq >= self.limit:
                    continue
                if view_shows(self.view, seq):
                    self.found = seq
                    self.finished = True
                    return True
            if now >= deadline:
                return False
