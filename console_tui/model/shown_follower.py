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
"""

from __future__ import annotations

from time import perf_counter

from .shown_rows import ShownPiece, shown_pieces
from .store import CHUNK_SIZE, LogStore
from .view import LogView


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
        store.evict_listeners.append(self._evicting)

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
        self.reset()

    def sync(self, budget_s: float | None = None, *, stop: int | None = None) -> bool:
        """Take in what arrived (and, after a rules change, everything again), for about
        ``budget_s`` (None: all of it); not past seq ``stop``. True when caught up."""
        if not self.enabled:
            return True
        self.follow_rules()
        if self.view.filtered and self.view.refiltering:
            return False  # the oldest records are not decided yet: wait for them
        store = self.store
        end = store.end_seq if stop is None else min(stop, store.end_seq)
        self.done_to = max(self.done_to, store.first_seq)
        deadline = None if budget_s is None else perf_counter() + budget_s
        while self.done_to < end:
            hi = end if deadline is None else min(end, self.done_to + CHUNK_SIZE)
            for piece in shown_pieces(store, self.view, self.done_to, hi):
                self.take(piece)
            self.done_to = hi
            if deadline is not None and perf_counter() >= deadline:
                break
        return self.done_to >= end

    def _evicting(self, first: int, new_first: int) -> None:
        self._all_shown = None  # what it kept counted records going now
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

    def set_enabled(self, enabled: bool) -> None:
        """Off: nothing is kept (and nothing costs); on again: rebuilt from the oldest record."""
        if enabled != self.enabled:
            self.enabled = enabled
            self._all_shown = None
            self.restart()
