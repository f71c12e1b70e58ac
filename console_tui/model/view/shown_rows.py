"""The records a ``LogView`` shows, read a store chunk at a time.

What the overview keeps (the timeline, the storms) counts the rows the table shows: it
reads them here, in seq order, as ``(chunk, offsets)`` pieces, so that it can take a
chunk's columns (stamps, levels, nodes, texts) at the offsets it needs without a lookup
per record.
"""

from __future__ import annotations

from array import array
from bisect import bisect_left
from collections.abc import Iterator, Sequence
from typing import NamedTuple

from ..store.consecutive import shifted
from ..store.log_store import Chunk, LogStore
from .log_view import LogView


class ShownPiece(NamedTuple):
    """Shown records of one chunk: ``chunk``'s records at ``offsets``; ``base`` is the seq of offset 0."""

    chunk: Chunk
    base: int
    offsets: Sequence[int]

    def seqs(self) -> Sequence[int]:
        offsets = self.offsets
        if isinstance(offsets, range):
            return range(self.base + offsets.start, self.base + offsets.stop)
        return shifted(offsets, self.base) if isinstance(offsets, array) else [self.base + offset for offset in offsets]


def shown_pieces(store: LogStore, view: LogView, lo: int, hi: int) -> Iterator[ShownPiece]:
    """The records of seqs ``lo:hi`` (clamped to what is kept) that ``view`` shows, oldest
    first. Only seqs the view has decided count: call it when it is not refiltering, or
    for seqs it took in with ``update`` since."""
    lo, hi = max(lo, store.first_seq), min(hi, store.end_seq)
    if lo >= hi:
        return
    if not view.filtered:
        for span in store.spans(lo, hi):
            yield ShownPiece(span.chunk, span.seq - span.lo, range(span.lo, span.hi))
        return
    first_row, end_row = view.row_of(lo), view.row_of(hi)
    if first_row >= end_row:
        return
    seqs = view.seqs_of_rows(first_row, end_row)
    at = 0
    for span in store.spans(lo, hi):
        base = span.seq - span.lo
        end = bisect_left(seqs, base + span.hi, at)
        if end > at:
            yield ShownPiece(span.chunk, base, shifted(seqs[at:end], -base))
        at = end
