"""The table's rows: which stored records are shown, in order.

A ``LogView`` maps row numbers to store seqs. With no filter every kept record is a row
(no index is built); with a filter, an index of the seqs that pass is extended as
records arrive (each new record is tested once) and trimmed lazily as the store evicts.
"""

from __future__ import annotations

from array import array
from bisect import bisect_left
from collections.abc import Callable, Iterable

from .store import ChunkSpan, LogStore

#: Given the store and a span of it, the seqs in the span that are shown, in order.
SpanFilter = Callable[[LogStore, ChunkSpan], Iterable[int]]


class LogView:
    """Rows of the table over a ``LogStore``, optionally filtered."""

    def __init__(self, store: LogStore, span_filter: SpanFilter | None = None) -> None:
        self.store = store
        self._filter: SpanFilter | None = None
        self._index = array("q")  # seqs that pass, ascending; entries < store.first_seq are stale
        self._start = 0  # first live entry of _index
        self._indexed_to = store.first_seq  # seqs below this have been tested
        self.set_filter(span_filter)

    @property
    def filtered(self) -> bool:
        return self._filter is not None

    def set_filter(self, span_filter: SpanFilter | None) -> None:
        """Use a new filter and re-index every kept record."""
        self._filter = span_filter
        self._index = array("q")
        self._start = 0
        self._indexed_to = self.store.first_seq
        self.update()

    def rebuild(self) -> None:
        """Re-index from scratch (after the store was cleared)."""
        self.set_filter(self._filter)

    def update(self) -> None:
        """Take in records appended (and forget those evicted) since the last call."""
        store = self.store
        if self._filter is None:
            return
        self._trim()
        start = max(self._indexed_to, store.first_seq)
        if start < store.end_seq:
            for span in store.spans(start, store.end_seq):
                self._index.extend(self._filter(store, span))
        self._indexed_to = store.end_seq

    def _trim(self) -> None:
        first = self.store.first_seq
        index = self._index
        if self._start < len(index) and index[self._start] < first:
            self._start = bisect_left(index, first, self._start)
        if self._start > 4096 and self._start * 2 > len(index):
            del index[: self._start]
            self._start = 0

    def __len__(self) -> int:
        if self._filter is None:
            return len(self.store)
        self._trim()
        return len(self._index) - self._start

    def seq_at(self, row: int) -> int:
        """The seq shown at ``row`` (0 is the oldest row); ``IndexError`` past the end."""
        if row < 0:
            raise IndexError(row)
        if self._filter is None:
            if row >= len(self.store):
                raise IndexError(row)
            return self.store.first_seq + row
        return self._index[self._start + row]

    def row_of(self, seq: int) -> int:
        """The row showing ``seq``, or the row of the next shown record after it."""
        if self._filter is None:
            return min(max(seq - self.store.first_seq, 0), len(self.store))
        self._trim()
        return bisect_left(self._index, seq, self._start) - self._start

    def count_before(self, seq: int) -> int:
        """How many rows show records older than ``seq``."""
        return self.row_of(seq)
