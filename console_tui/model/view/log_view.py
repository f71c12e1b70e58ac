"""The table's rows: which stored records are shown, in order, and how each is marked.

A ``LogView`` maps row numbers to store seqs under a ``RuleSet``. With no active rule every
kept record is a row (no index is built). Otherwise an index of the seqs that pass is kept:

- records that arrive are tested once, in ``update()``;
- when the rules change (``set_rules``) the rows around a seq (``around``: the record the
  reader is on; else the newest) are filtered at once (the first screen), and the rest by
  ``refilter_step(budget)``, outwards from there, in small pieces that the caller runs from a
  timer or when idle. Meanwhile the rows are those done so far; records that arrive wait
  until the records before them are done; records evicted meanwhile simply drop out.

Each rule's match mask is kept per store chunk (``rule_masks.py``), so counts per rule are
cheap, a rule is never tested twice on a record, and switching entries on and off, inverting
them or moving them between exclude and highlight only recombines masks.

No rule can freeze the caller: each test of a span runs under a time limit (``time_limit``),
and a rule that runs past it (a catastrophic regex) is switched off, not applied: the view
goes on under the rules without it and lists it in ``switched_off`` for the caller to tell.
``stop_filtering()`` switches off the rules still being applied (Esc in the app).
"""

from __future__ import annotations

from array import array
from bisect import bisect_left, bisect_right
from collections.abc import Callable
from itertools import compress
from operator import neg
from time import perf_counter

from ..inert_text import plural
from ..rules.rule import Rule, SpanTest
from ..rules.ruleset import Decoration, RuleSet
from ..rules.time_limit import MatchTimeout, alarms, time_limit
from ..store.consecutive import consecutive
from ..store.log_store import CHUNK_SIZE, Chunk, ChunkSpan, LogStore
from .rule_masks import RuleMasks

#: Rows filtered synchronously when the rules change (more than a screen).
FIRST_SCREEN_ROWS = 200
#: Longest the synchronous part of ``set_rules`` keeps looking for the first screen.
FIRST_SCREEN_BUDGET_S = 0.03
_MIN_PIECE, _START_PIECE = 32, 1024
#: Longest one test of a rule over a span of records may take before the rule counts as too slow.
RULE_LIMIT_S = 0.25


class _TooSlow(Exception):
    def __init__(self, rule: Rule, rows: int, seconds: float) -> None:
        super().__init__(rule)
        self.rule, self.rows, self.seconds = rule, rows, seconds


class LogView:
    """Rows of the table over a ``LogStore`` under a ``RuleSet``."""

    def __init__(self, store: LogStore, rules: RuleSet | None = None, *, rule_limit_s: float = RULE_LIMIT_S) -> None:
        self.store = store
        self.rules = RuleSet()
        self.rule_limit_s = rule_limit_s
        #: Seconds, for the budgets of ``set_rules`` and ``refilter_step`` (and a search's): tests set their own.
        self.clock: Callable[[], float] = perf_counter
        #: Rules switched off because they were too slow, with why (taken by ``take_switched_off``).
        self.switched_off: list[tuple[Rule, str]] = []
        #: Active rules whose answers over the kept records are not complete yet.
        self._unfinished: set[Rule] = set()
        self._tests: dict[Rule, SpanTest] = {}
        self._masks = RuleMasks(store.first_seq)
        self._indexed = False
        self._reset_index()
        self._piece = _START_PIECE
        #: The seq the rows were last filtered around (None: the newest).
        self.around: int | None = None
        #: The store rewrote records the index holds, beyond trimming: index again (``update``).
        self._stale = False
        self.set_rules(rules or RuleSet())
        store.rewind_listeners.append(self._rewinding)

    def _reset_index(self) -> None:
        # Rows are ``reversed(_front) + _back[_start:]``: the refiltered part (seqs descending,
        # extended at the end as older records are done) then the part kept since.
        self._front = array("q")
        self._front_marks = bytearray()  # 1 where the row is highlighted
        self._back = array("q")
        self._back_marks = bytearray()
        self._start = 0  # first live entry of _back
        self._pending_lo = self._pending_hi = self.store.first_seq  # seqs still to refilter
        self._indexed_to = self.store.end_seq  # seqs below this are in the index (or pending)
        #: Records from ``_indexed_to`` on are still to refilter (oldest first, into ``_back``).
        self._rising = False

    # -- rules ------------------------------------------------------------------------------

    @property
    def filtered(self) -> bool:
        """Some records may be hidden (not every kept record is a row)."""
        return self.rules.filtering

    @property
    def highlighting(self) -> bool:
        return self.rules.highlighting

    def set_rules(
        self,
        rules: RuleSet,
        *,
        first_screen: int = FIRST_SCREEN_ROWS,
        budget_s: float = FIRST_SCREEN_BUDGET_S,
        around: int | None = None,
    ) -> None:
        """Use new rules: ``first_screen`` rows each side of seq ``around`` (the newest when
        None) at once (within ``budget_s``), the rest by ``refilter_step``. A rule too slow to
        test is switched off (``switched_off``)."""
        self.around = around
        with alarms():
            while True:
                try:
                    self._set_rules(rules, first_screen, budget_s)
                    return
                except _TooSlow as slow:
                    rules = self._switch_off(slow)

    def _switch_off(self, slow: _TooSlow) -> RuleSet:
        """The rules in force without the rule that was too slow (noted in ``switched_off``)."""
        rows = plural(slow.rows, "message")
        self.switched_off.append((slow.rule, f"too slow: testing {rows} took over {slow.seconds:g} s"))
        self._unfinished.discard(slow.rule)
        return self.rules.without_rules({slow.rule})

    def take_switched_off(self) -> list[tuple[Rule, str]]:
        """Rules switched off since the last call, with why."""
        taken, self.switched_off = self.switched_off, []
        return taken

    def stop_filtering(self) -> list[Rule]:
        """Switch off the rules still being applied (the rules before them stay); returns them."""
        unfinished = [rule for rule in self.rules.active_rules() if rule in self._unfinished]
        if unfinished and self.refiltering:
            self.set_rules(self.rules.without_rules(set(unfinished)), around=self.around)
            return unfinished
        return []

    def _set_rules(self, rules: RuleSet, first_screen: int, budget_s: float) -> None:
        store = self.store
        self.rules = rules
        active = rules.active_rules()
        fresh = [rule for rule in active if rule not in self._tests]
        if fresh:
            self._piece = min(self._piece, _START_PIECE)  # a new rule's cost is not known yet
        self._unfinished = {rule for rule in active if rule in self._unfinished} | set(fresh)
        self._tests = {rule: self._tests.get(rule) or rule.compile(store) for rule in active}
        self._masks.keep_only(entry.rule for entry in rules.entries)
        self._indexed = bool(active)
        self._reset_index()
        if self._indexed:
            origin = store.end_seq if self.around is None else min(max(self.around, store.first_seq), store.end_seq)
            self._pending_lo, self._pending_hi = store.first_seq, origin
            self._indexed_to, self._rising = origin, origin < store.end_seq
            deadline = self.clock() + budget_s
            pieces = 0  # a piece each way at least (``around``'s own first), then while there is time
            while pieces < 2 or self.clock() < deadline:
                rise = self._rising_pending and len(self._back) < first_screen
                fall = self._falling_pending and len(self._front) < first_screen
                if rise and (pieces % 2 == 0 or not fall):
                    self._rise_piece(self._piece)
                elif fall:
                    self._refilter_piece(self._piece)
                else:
                    break
                pieces += 1
        if not self.refiltering:
            self._unfinished.clear()
            self._rising = False

    def rebuild(self) -> None:
        """Re-index from scratch (after the store was cleared)."""
        self._masks.clear()
        self.set_rules(self.rules)

    @property
    def _falling_pending(self) -> bool:
        """Records older than those done are still to be filtered."""
        return self._pending_hi > max(self._pending_lo, self.store.first_seq)

    @property
    def _rising_pending(self) -> bool:
        """Records newer than those done (there when the rules changed, or since) are still to be filtered."""
        return self._rising and self._indexed_to < self.store.end_seq

    @property
    def refiltering(self) -> bool:
        """Records are still to be filtered under the current rules."""
        return self._falling_pending or self._rising_pending

    @property
    def pending(self) -> int:
        """Records still to be filtered under the current rules."""
        first = self.store.first_seq
        falling = max(self._pending_hi - max(self._pending_lo, first), 0)
        rising = self.store.end_seq - max(self._indexed_to, first) if self._rising_pending else 0
        return falling + rising

    def refilter_step(self, budget_s: float = 0.008) -> bool:
        """Filter older records, newest first, for about ``budget_s``; True when all are done."""
        try:
            with alarms():
                done = self._refilter_step(budget_s)
        except _TooSlow as slow:
            self.set_rules(self._switch_off(slow), around=self.around)
            done = not self.refiltering
        if done:
            self._unfinished.clear()
            self._rising = False
        return done

    def _refilter_step(self, budget_s: float) -> bool:
        if not self.refiltering:
            return True
        self._trim()
        clock = self.clock
        deadline = clock() + budget_s
        while self.refiltering:
            began = clock()
            if self._rising_pending:
                rows = self._rise_piece(self._piece)
            else:
                rows = self._refilter_piece(self._piece)
            now = clock()
            if rows:
                # Size pieces to about a quarter of the budget, so a step overshoots little.
                per_row = max(now - began, 1e-9) / rows
                self._piece = min(max(int(budget_s / 4 / per_row), _MIN_PIECE), CHUNK_SIZE)
            if now >= deadline:
                break
        return not self.refiltering

    def _refilter_piece(self, rows: int) -> int:
        hi = self._pending_hi
        lo = hi - rows
        chunk_start = self.store.chunk_start(hi - 1)
        if hi - chunk_start <= 4 * rows:  # pieces are a quarter of a step's budget: fits in one
            lo = chunk_start  # the rest of the chunk: rules test whole chunks fastest (packed texts)
        lo = max(self._pending_lo, self.store.first_seq, lo)
        front, marks = self._front, self._front_marks
        for span in self.store.spans(lo, hi, newest_first=True):
            seqs, highlighted = self._evaluate(span, descending=True)
            front.extend(seqs)
            marks.extend(highlighted)
        self._pending_hi = lo
        return hi - lo

    def _rise_piece(self, rows: int) -> int:
        """Filter about ``rows`` records from ``_indexed_to`` on (to the end of a chunk)."""
        store = self.store
        lo = max(self._indexed_to, store.first_seq)
        hi = min(lo + rows, store.end_seq)
        chunk_end = store.chunk_start(lo) + CHUNK_SIZE
        if chunk_end - lo <= 4 * rows:
            hi = min(max(hi, chunk_end), store.end_seq)
        for span in store.spans(lo, hi):
            seqs, highlighted = self._evaluate(span)
            self._back.extend(seqs)
            self._back_marks.extend(highlighted)
        self._indexed_to = hi
        if hi >= store.end_seq:
            self._rising = False
        return hi - lo

    def update(self) -> None:
        """Take in records appended (and forget those evicted) since the last call."""
        try:
            with alarms():
                self._update()
        except _TooSlow as slow:
            self.set_rules(self._switch_off(slow), around=self.around)

    def _update(self) -> None:
        if self._stale:
            self._stale = False
            self.set_rules(self.rules, around=self.around)
            return
        if not self._indexed or self._rising_pending:  # newer ones wait for those before them
            return
        store = self.store
        self._trim()
        start = max(self._indexed_to, store.first_seq)
        for span in store.spans(start, store.end_seq):
            seqs, highlighted = self._evaluate(span)
            self._back.extend(seqs)
            self._back_marks.extend(highlighted)
        self._indexed_to = store.end_seq

    # -- testing spans ----------------------------------------------------------------------

    def _evaluate(self, span: ChunkSpan, *, descending: bool = False) -> tuple[array, bytes]:
        """The seqs of ``span`` that are shown, and their highlight marks (newest first when
        ``descending``)."""
        chunk, lo, hi, seq = span
        size = hi - lo
        base = seq - lo
        masks = {rule: self._masks.mask(base, chunk, rule, lo, hi, self._test) for rule in self._tests}
        shown, highlighted = self.rules.decide(masks, size)
        if shown.count(0) == 0:  # every record shown (highlight rules only, say): no per-record work
            seqs = consecutive(seq, size, descending=descending)
        else:
            seqs = array("q", compress(range(seq, seq + size), shown))
            highlighted = bytes(compress(highlighted, shown))
            if descending:
                seqs.reverse()
        return seqs, highlighted[::-1] if descending else highlighted

    def _test(self, rule: Rule, chunk: Chunk, lo: int, hi: int) -> bytes:
        """The rule's test of ``chunk[lo:hi]``, abandoned past ``rule_limit_s``."""
        try:
            with time_limit(self.rule_limit_s):
                return self._tests[rule](chunk, lo, hi)
        except MatchTimeout:
            raise _TooSlow(rule, hi - lo, self.rule_limit_s) from None

    def match_counts(self) -> list[int | None]:
        """For each entry of the rules: kept records its rule matches (inverted: does not
        match), among those tested so far; ``None`` for entries that are not active."""
        counts: list[int | None] = []
        for entry in self.rules.entries:
            if not entry.active or entry.rule not in self._tests:
                counts.append(None)
                continue
            matched, tested = self._masks.count(entry.rule, self.store.first_seq)
            counts.append(tested - matched if entry.inverted else matched)
        return counts

    # -- eviction ---------------------------------------------------------------------------

    def _trim(self) -> None:
        first = self.store.first_seq
        front = self._front
        if front and front[-1] < first:
            keep = bisect_right(front, -first, key=neg)  # entries >= first (descending array)
            del front[keep:]
            del self._front_marks[keep:]
        back = self._back
        if self._start < len(back) and back[self._start] < first:
            self._start = bisect_left(back, first, self._start)
        if self._start > 4096 and self._start * 2 > len(back):
            del back[: self._start]
            del self._back_marks[: self._start]
            self._start = 0
        self._masks.drop_evicted(first)

    def _rewinding(self, start: int) -> None:
        """The store writes its records from ``start`` on again: forget what was decided of them
        (the index is cut there, or made again at the next ``update`` while still refiltering)."""
        self._masks.drop_from(start)
        if not self._indexed:
            return
        if self.refiltering or (self._front and self._front[0] >= start):
            self._stale = True
            return
        cut = bisect_left(self._back, start, self._start)
        del self._back[cut:]
        del self._back_marks[cut:]
        self._indexed_to = min(self._indexed_to, start)

    # -- rows -------------------------------------------------------------------------------

    def __len__(self) -> int:
        if not self._indexed:
            return len(self.store)
        self._trim()
        return len(self._front) + len(self._back) - self._start

    def seq_at(self, row: int) -> int:
        """The seq shown at ``row`` (0 is the oldest row); ``IndexError`` past the end."""
        if row < 0:
            raise IndexError(row)
        if not self._indexed:
            if row >= len(self.store):
                raise IndexError(row)
            return self.store.first_seq + row
        older = len(self._front)
        if row < older:
            return self._front[older - 1 - row]
        return self._back[self._start + row - older]

    def seqs_of_rows(self, first: int, end: int) -> array:
        """The seqs shown at rows ``first:end`` (clamped to the rows there are), oldest first:
        one slice of the index each way, no lookup per row."""
        first, end = max(first, 0), min(end, len(self))
        if first >= end:
            return array("q")
        if not self._indexed:
            return consecutive(self.store.first_seq + first, end - first)
        front, older = self._front, len(self._front)
        seqs = front[older - min(end, older) : older - first] if first < older else array("q")
        seqs.reverse()
        if end > older:
            start = self._start
            seqs.extend(self._back[start + max(first - older, 0) : start + end - older])
        return seqs

    def row_of(self, seq: int) -> int:
        """The row showing ``seq``, or the row of the next shown record after it."""
        if not self._indexed:
            return min(max(seq - self.store.first_seq, 0), len(self.store))
        self._trim()
        front = self._front
        if front and seq <= front[0]:
            return len(front) - bisect_right(front, -seq, key=neg)
        return len(front) + bisect_left(self._back, seq, self._start) - self._start

    def count_before(self, seq: int) -> int:
        """How many rows show records older than ``seq``."""
        return self.row_of(seq)

    def row_shown(self, seq: int) -> int | None:
        """The row showing ``seq``; None when no row does (the rules hide it, or it is gone)."""
        row = self.row_of(seq)
        return row if row < len(self) and self.seq_at(row) == seq else None

    def decoration_of(self, seq: int) -> Decoration:
        """How the row of ``seq`` is marked: "highlight", "dim", or None (no highlight rules)."""
        if not self._indexed or not self.rules.highlighting:
            return None
        front = self._front
        if front and seq <= front[0]:
            at = bisect_left(front, -seq, key=neg)
            found = at < len(front) and front[at] == seq and self._front_marks[at]
        else:
            back = self._back
            at = bisect_left(back, seq, self._start)
            found = at < len(back) and back[at] == seq and self._back_marks[at]
        return "highlight" if found else "dim"
