"""Keeping up with the rows a view shows: the common part of the timeline and the storms.

A follower takes in the shown records in seq order, a piece at a time (``take``), and lets
go of those the store drops at its bound (``forget``, called from the store's eviction
hook while they can still be read). When the rules change it starts again from the
oldest record (``reset``), once the view has decided every record under the new rules,
and catches up in budgeted steps (``sync``), so a million records never stall a frame.

Two rule changes cost nothing: between rules that hide no record (none at all, or only
highlight rules) nothing changes, and back to such rules from rules that hid records, what
was taken in under them is taken back (``state``/``restore``, kept while nothing was
dropped), and only the records that arrived since are taken in: hiding a level and showing
it again recounts nothing.

What does not depend on the rules is worked out once for a full chunk (``chunk_fact``: its
stamps in order, the nodes that repeat a text in it), so taking a chunk in again after a rule
change can skip work its facts make needless.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from time import perf_counter
from typing import Any, TypeVar

from ..store.log_store import CHUNK_SIZE, Chunk, LogStore
from ..view.log_view import LogView
from ..view.shown_rows import ShownPiece, shown_pieces

_Fact = TypeVar("_Fact")


class ShownFollower:
    """Takes in ``view``'s shown records as they arrive; ``reset``/``take``/``forget`` are its subclass's."""

    def __init__(self, store: LogStore, view: LogView) -> None:
        self.store = store
        self.view = view
        self._rules = view.rules
        #: Shown records with seqs below this have been taken in.
        self.done_to = store.first_seq
        #: Seqs below this were there when the follower (re)started: catching up to it is rebuilding.
        self._rebuild_to = store.end_seq
        self.enabled = True
        #: What was taken in while every record was shown, for going back to that: (the store's
        #: first seq then, ``done_to``, ``state()``).
        self._all_shown: tuple[int, int, object] | None = None
        #: (a full chunk's first seq, what) -> a fact about it (``chunk_fact``).
        self._facts: dict[tuple[int, str], Any] = {}
        store.evict_listeners.append(self._evicting)
        store.rewind_listeners.append(self._rewinding)

    # -- what subclasses do -----------------------------------------------------------------------

    def reset(self) -> None:
        """Forget everything taken in (the rules changed, the store was cleared)."""

    def take(self, piece: ShownPiece) -> None:
        """Take in shown records (seq order, after every record taken before)."""

    def forget(self, piece: ShownPiece) -> None:
        """Let go of records taken in before, which the store is about to drop."""

    def forgotten(self, new_first: int) -> None:
        """The records before ``new_first`` were all given to ``forget`` (and can still be read)."""

    def state(self) -> object:
        """What was taken in, to be put back by ``restore`` (``reset`` must not change it)."""
        return None

    def restore(self, state: object) -> None:
        """Put back what ``state`` returned."""

    def chunk_fact(self, piece: ShownPiece, what: str, compute: Callable[[Chunk], _Fact]) -> _Fact | None:
        """``compute(chunk)`` for the piece's chunk, worked out once while the chunk is full
        (it never changes then; seqs are never used again); None while it fills."""
        if len(piece.chunk) < CHUNK_SIZE:
            return None
        key = (piece.base, what)
        fact = self._facts.get(key)
        if fact is None:
            fact = self._facts[key] = compute(piece.chunk)
        return fact

    def _forget_facts(self, first: int) -> None:
        """Forget the facts of chunks wholly before seq ``first``."""
        for key in [key for key in self._facts if key[0] + CHUNK_SIZE <= first]:
            del self._facts[key]

    # -- keeping up -------------------------------------------------------------------------------

    @property
    def rebuilding(self) -> bool:
        """Catching up on records that were there when the rules changed (or it started)."""
        return self.enabled and self.done_to < min(self._rebuild_to, self.store.end_seq)

    @property
    def behind(self) -> bool:
        """Records arrived (or are still to be taken in again) that ``sync`` has not taken in."""
        return self.enabled and (self.done_to < self.store.end_seq or self.view.rules is not self._rules)

    def follow_rules(self) -> None:
        """The view's rules changed: start again, unless the change shows the same records."""
        old, new = self._rules, self.view.rules
        if new is old:
            return
        store = self.store
        if not old.filtering:
            if not new.filtering:
                self._rules = new  # the same records shown: nothing to count again
                return
            if self.enabled and self.done_to >= store.end_seq:
                self._all_shown = (store.first_seq, self.done_to, self.state())
        kept, self._all_shown = self._all_shown, (None if not new.filtering else self._all_shown)
        if not new.filtering and kept is not None and kept[0] == store.first_seq and self.enabled:
            self._rules = new
            self.done_to = kept[1]
            self._rebuild_to = store.end_seq
            self.restore(kept[2])
            return
        self.restart()

    def restart(self) -> None:
        """Start again from the oldest record (after ``clear``, or to be sure)."""
        self._rules = self.view.rules
        self.done_to = self.store.first_seq
        self._rebuild_to = self.store.end_seq
        self._forget_facts(self.store.first_seq)  # (the store was cleared)
        self.reset()

    def sync(self, budget_s: float | None = None, *, stop: int | None = None) -> bool:
        """Take in what arrived (and, after a rules change, everything again), for about
        ``budget_s`` (None: all of it); not past seq ``stop``. True when caught up."""
        return sync_together((self,), budget_s, stop=stop)

    def synced(self) -> None:
        """After each ``sync`` (a subclass's chance to settle what it shows)."""

    def _ready(self) -> bool:
        """Following the view's rules, and able to take records in (the view decided them)."""
        self.follow_rules()
        if self.view.filtered and self.view.refiltering:
            return False  # the oldest records are not decided yet: wait for them
        self.done_to = max(self.done_to, self.store.first_seq)
        return True

    def _evicting(self, first: int, new_first: int) -> None:
        self._all_shown = None  # what it kept counted records going now
        self._forget_facts(new_first)
        if not self.enabled:
            return
        self.follow_rules()
        if self.view.filtered and self.view.refiltering:
            # The view cannot say yet which of the records going were shown: start again.
            self.restart()
        else:
            for piece in shown_pieces(self.store, self.view, first, min(new_first, self.done_to)):
                self.forget(piece)
            self.forgotten(new_first)
        self.done_to = max(self.done_to, new_first)

    def _rewinding(self, start: int) -> None:
        """The store writes its records from ``start`` on again, in another order: what was
        taken in follows their order, so it starts again (rare: a late history)."""
        self._all_shown = None
        if self.enabled and self.done_to > start:
            self.restart()

    def set_enabled(self, enabled: bool) -> None:
        """Off: nothing is kept (and nothing costs); on again: rebuilt from the oldest record."""
        if enabled != self.enabled:
            self.enabled = enabled
            self._all_shown = None
            self.restart()


def sync_together(
    followers: Sequence[ShownFollower], budget_s: float | None = None, *, stop: int | None = None
) -> bool:
    """``sync`` for followers of one view, in one pass: the shown records of each store chunk
    are read once for all of them, while they are at the same place (after a rule change they
    all start again from the oldest record). True when all are caught up."""
    try:
        return _sync_together([follower for follower in followers if follower.enabled], budget_s, stop)
    finally:
        for follower in followers:
            follower.synced()


def _sync_together(going: list[ShownFollower], budget_s: float | None, stop: int | None) -> bool:
    if not going:
        return True
    if not all([follower._ready() for follower in going]):
        return False
    if len({follower.done_to for follower in going}) > 1:
        # Apart (one was switched on again, say): each on its own, so that none waits for another.
        share = None if budget_s is None else budget_s / len(going)
        return all([_sync_together([follower], share, stop) for follower in going])
    store, view = going[0].store, going[0].view
    end = store.end_seq if stop is None else min(stop, store.end_seq)
    deadline = None if budget_s is None else perf_counter() + budget_s
    while going[0].done_to < end:
        lo = going[0].done_to
        hi = min(end, store.chunk_start(lo) + CHUNK_SIZE)
        pieces = list(shown_pieces(store, view, lo, hi))
        for follower in going:
            for piece in pieces:
                follower.take(piece)
            follower.done_to = hi
        if deadline is not None and perf_counter() >= deadline:
            break
    return going[0].done_to >= end
