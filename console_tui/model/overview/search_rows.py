"""A search's matches counted as the table shows them: a collapsed storm is one row, however
many of its messages match ("match 2 of 3", in 3 rows, 150 messages).

A storm's repeats have its first message's text (with ``mask_digits``, once digits are
masked): without masking, all of them match when the first does; with it, the matches
among its messages are looked up one by one.
"""

from __future__ import annotations

from bisect import bisect_right
from itertools import accumulate

from ..view.search_walk import Search
from .storms import Storm, StormRows


class MatchRows:
    """The rows holding matches of ``search`` (complete) among ``storms``' rows."""

    def __init__(self, search: Search, storms: StormRows) -> None:
        self.search = search
        self.store = storms.store
        #: Matching messages.
        self.messages = search.count()
        collapsed = storms.collapsed_storms() if storms.enabled else []
        self._storms: list[Storm] = []
        hidden, extra = [], []
        for storm in collapsed:
            head_matches = search.is_match(storm.head)
            if storms.mask_digits:
                members = len(self._members(storm, storm.head))
            else:
                members = storm.count - 1 if head_matches else 0
            if members:
                self._storms.append(storm)
                hidden.append(members)
                extra.append(0 if head_matches else 1)
        self._heads = [storm.head for storm in self._storms]
        self._hidden = list(accumulate(hidden, initial=0))
        self._extra = list(accumulate(extra, initial=0))
        #: Rows holding a match.
        self.rows = self.messages - self._hidden[-1] + self._extra[-1]

    def _members(self, storm: Storm, after: int) -> list[int]:
        """The storm's matching messages after seq ``after``."""
        store = self.store
        found = self.search.between(after + 1, storm.last + 1)
        return [seq for seq in found if seq in store and store.node_id_of(seq) == storm.node]

    def index(self, seq: int) -> int | None:
        """1-based place among the match rows of the row starting at ``seq`` (a match, or a
        storm holding one), or None when that row holds no match."""
        at = bisect_right(self._heads, seq)
        if not (at and self._heads[at - 1] == seq) and not self.search.is_match(seq):
            return None
        hidden = self._hidden[at]
        for storm in self._storms[:at]:
            if storm.last > seq:  # its repeats reach past the row (other nodes' rows between)
                hidden -= len(self._members(storm, seq))
        return self.search.count(seq + 1) - hidden + self._extra[at]
