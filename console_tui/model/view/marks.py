"""Marks: rows a person put a mark on, to come back to (lnav's bookmarks).

Marks are kept by seq, so they stay on their message whatever the rules show, and go when
the message is evicted. Jumping between them passes over those the rules hide.
"""

from __future__ import annotations

from bisect import bisect_left, bisect_right, insort
from collections.abc import Callable, Iterator


class Marks:
    """A sorted set of marked seqs."""

    def __init__(self) -> None:
        self._seqs: list[int] = []

    def toggle(self, seq: int) -> bool:
        """Mark ``seq``, or take its mark off; True when it is marked now."""
        at = bisect_left(self._seqs, seq)
        if at < len(self._seqs) and self._seqs[at] == seq:
            del self._seqs[at]
            return False
        insort(self._seqs, seq)
        return True

    def discard(self, seq: int) -> None:
        at = bisect_left(self._seqs, seq)
        if at < len(self._seqs) and self._seqs[at] == seq:
            del self._seqs[at]

    def clear(self) -> None:
        self._seqs.clear()

    def trim(self, first_seq: int) -> None:
        """Forget marks on evicted messages."""
        if self._seqs and self._seqs[0] < first_seq:
            del self._seqs[: bisect_left(self._seqs, first_seq)]

    def move(self, moved: dict[int, int]) -> None:
        """Messages moved to other seqs (old -> new: a late history placed by its stamp): their marks go with them."""
        if moved and self._seqs:
            self._seqs = sorted(moved.get(seq, seq) for seq in self._seqs)

    def __contains__(self, seq: object) -> bool:
        if not isinstance(seq, int):
            return False
        at = bisect_left(self._seqs, seq)
        return at < len(self._seqs) and self._seqs[at] == seq

    def __len__(self) -> int:
        return len(self._seqs)

    def __iter__(self) -> Iterator[int]:
        return iter(list(self._seqs))

    def nearest(self, seq: int, *, forward: bool, shown: Callable[[int], bool]) -> int | None:
        """The nearest mark after ``seq`` (before it, backward) that ``shown`` accepts."""
        seqs = self._seqs
        if forward:
            candidates = seqs[bisect_right(seqs, seq) :]
        else:
            candidates = seqs[: bisect_left(seqs, seq)][::-1]
        return next((mark for mark in candidates if shown(mark)), None)
