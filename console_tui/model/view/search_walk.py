"""Search: find a text or a regex in the messages without hiding any row.

``parse_search`` reads what a person types: ``timeout`` (ignoring case unless it has a
capital letter, as the query line does), ``/time(out|d out)/`` a regular expression,
``/.../i`` ignoring case. It gives a ``TextMatch``, the same matcher the rules use, so a
pattern means the same in both and a bad one is refused the same way.

``Search`` finds every shown row whose message matches, walking out from an anchor (the
selected row) in both directions, a time budget at a time: the match nearest the anchor in
the direction asked for is known first, and "match 3 of 17" once the walk is complete. New
records are walked as they arrive; a change of the rules needs a new ``Search`` (which rows
are shown changed).

Messages are tested as the message rule tests them (``rules/message.py``): on a full chunk's
packed text all at once where the match allows (``rules/packed_match.py``), else one by one;
a regex under ``time_limit``. A search looks for something rare, so first the plain text
every match holds (``must_hold``) is looked for in a full chunk's packed text with one
``re`` search (faster than ``str.find`` on such text): where it is absent, no message of the
span matches, and the test starts at the first message holding it.
"""

from __future__ import annotations

import re
from array import array
from bisect import bisect_left, bisect_right
from collections.abc import Callable, Iterator, Sequence
from itertools import compress
from operator import neg

from ..rules.message import messages_test
from ..rules.packed_match import lowered
from ..rules.pattern_match import TextMatch
from ..rules.regex_shape import required_literal
from ..rules.time_limit import MatchTimeout, time_limit
from ..store.log_store import Chunk, LogStore
from ..store.packed_texts import PackedTexts
from .log_view import LogView
from .seek import HITS_LIMIT_S, Hits, PieceSize, Walk, view_shows


def parse_search(text: str) -> TextMatch:
    """What the search line's text looks for; ``RuleError`` for a bad regex."""
    stripped = text.strip()
    if len(stripped) >= 2 and stripped.startswith("/"):
        if stripped.endswith("/i") and len(stripped) >= 3:
            return TextMatch(stripped[1:-2], ignore_case=True, regex=True)
        if stripped.endswith("/"):
            return TextMatch(stripped[1:-1], regex=True)
    return TextMatch(stripped, ignore_case=stripped == stripped.lower(), regex=False)


def describe_search(match: TextMatch) -> str:
    """How the status line names a search: ``'timeout'``, ``/time(out)/i``."""
    if match.regex:
        return f"/{match.text}/" + ("i" if match.ignore_case else "")
    return repr(match.text)


def display_pattern(match: TextMatch) -> re.Pattern[str]:
    """A regex finding the matches in a row's text as shown, for marking them."""
    if match.regex:
        return match.pattern()
    return re.compile(re.escape(match.text), re.IGNORECASE if match.ignore_case else 0)


def must_hold(match: TextMatch) -> tuple[str, bool]:
    """Plain text every message matching ``match`` holds ("" when there is none to look
    for), and whether it is to be looked for in the lower-cased text (ignoring case; the
    text is then ASCII, as the message rule's packed matchers have it)."""
    if match.regex:
        if not match.text:
            return "", False  # the empty regex: every message matches
        pattern = match.pattern()
        ignore_case = bool(pattern.flags & re.IGNORECASE)
        text = required_literal(pattern).text
        if ignore_case:
            text = text.lower() if text.isascii() else ""
    else:
        ignore_case = match.ignore_case
        text = match.text.casefold() if ignore_case else match.text
    if not text or "\0" in text or (ignore_case and not text.isascii()):
        return "", False
    return text, ignore_case


#: ``first(chunk, lo, hi)``: the first message in ``lo:hi`` that may match (``hi``: none).
FirstCandidate = Callable[[Chunk, int, int], int]


def first_candidate(match: TextMatch) -> FirstCandidate | None:
    """The first message of a span holding ``must_hold``'s text, found in a full chunk's
    packed text (``lo`` for other chunks: any may match); None when there is no text to
    look for."""
    text, lower = must_hold(match)
    if not text:
        return None
    find = re.compile(re.escape(text)).search

    def first(chunk: Chunk, lo: int, hi: int) -> int:
        texts = chunk.msgs
        if not isinstance(texts, PackedTexts) or lo >= hi:
            return lo
        haystack = lowered(texts) if lower else texts.text
        if haystack is None:
            return lo
        starts = texts.starts
        found = find(haystack, starts[lo], starts[hi] - 1)
        return hi if found is None else bisect_right(starts, found.start()) - 1

    return first


def text_hits(match: TextMatch) -> Hits:
    """The ``Hits`` of a ``TextMatch`` over messages: the message rule's own test (on a full
    chunk's packed text all at once where the match allows), as offsets, from the first
    message that may match (``first_candidate``)."""
    test = messages_test(match)
    first = first_candidate(match)

    def hits(chunk: Chunk, lo: int, hi: int) -> Sequence[int]:
        if first is not None:
            lo = first(chunk, lo, hi)
            if lo >= hi:
                return []
        return list(compress(range(lo, hi), test(chunk, lo, hi)))

    return hits


#: ``Search.nearest`` when the answer is not known yet (the walk has not got there).
PENDING = -1


class Search:
    """Every shown row matching ``match``, found from ``anchor`` outwards (see the module)."""

    def __init__(self, view: LogView, match: TextMatch, anchor: int) -> None:
        self.view = view
        self.store: LogStore = view.store
        self.match = match
        self.hits = text_hits(match)
        #: Only a regex can run long (plain text is found by ``str.find``).
        self._limit_s = HITS_LIMIT_S if match.regex else None
        self.up = Walk(self.store, anchor, forward=True)
        self.down = Walk(self.store, anchor, forward=False)
        #: Matches older than the anchor, newest first; then the anchor and newer, oldest first.
        self._older = array("q")
        self._newer = array("q")
        #: Why the search stopped (too slow a regex), or "".
        self.failed = ""
        self._piece = PieceSize()

    # -- walking ------------------------------------------------------------------------------

    @property
    def complete(self) -> bool:
        """Every kept record was looked at (until more arrive)."""
        return bool(self.failed) or (self.up.done and self.down.done)

    @property
    def older_done(self) -> bool:
        return bool(self.failed) or self.down.done

    @property
    def newer_done(self) -> bool:
        return bool(self.failed) or self.up.done

    def step(self, budget_s: float = 0.008, prefer: int = 0) -> bool:
        """Look on for about ``budget_s``: newer records first when ``prefer`` > 0, older
        when < 0, else both in turn. True when complete."""
        clock = self.view.clock  # the view's: tests inject one
        deadline = clock() + budget_s
        turn = 0
        while not self.complete:
            if prefer > 0 and not self.up.done:
                walk = self.up
            elif prefer < 0 and not self.down.done:
                walk = self.down
            else:
                walk = (self.up, self.down)[turn % 2]
                turn += 1
                if walk.done:
                    continue
            began = clock()
            if not self._walk_piece(walk):
                break
            now = clock()
            self._piece.learn(self._last_rows, now - began, budget_s)
            if now >= deadline:
                break
        self._trim()
        return self.complete

    _last_rows = 0

    def _walk_piece(self, walk: Walk) -> bool:
        span = walk.next_span(self._piece.rows)
        if span is None:
            return True
        self._last_rows = span.hi - span.lo
        try:
            if self._limit_s is None:
                offsets = self.hits(span.chunk, span.lo, span.hi)
            else:
                with time_limit(self._limit_s):
                    offsets = self.hits(span.chunk, span.lo, span.hi)
        except MatchTimeout:
            self.failed = f"too slow: testing {span.hi - span.lo:,} messages took over {self._limit_s:g} s"
            return False
        base = span.seq - span.lo
        view = self.view
        seqs = [base + offset for offset in offsets]
        if view.filtered:
            seqs = [seq for seq in seqs if view_shows(view, seq)]
        if walk.forward:
            self._newer.extend(seqs)
        else:
            seqs.reverse()
            self._older.extend(seqs)
        return True

    def _trim(self) -> None:
        """Forget matches evicted from the store."""
        first = self.store.first_seq
        older = self._older
        if older and older[-1] < first:
            del older[bisect_right(older, -first, key=neg) :]
        newer = self._newer
        if newer and newer[0] < first:
            del newer[: bisect_left(newer, first)]

    # -- answers ------------------------------------------------------------------------------

    def seqs(self) -> Iterator[int]:
        """The matches found so far, oldest first."""
        self._trim()
        yield from reversed(self._older)
        yield from self._newer

    def count(self, limit: int | None = None) -> int:
        """Matches found so far (those before seq ``limit`` only, when given)."""
        self._trim()
        older, newer = self._older, self._newer
        if limit is None:
            return len(older) + len(newer)
        return len(older) - bisect_right(older, -limit, key=neg) + bisect_left(newer, limit)

    def between(self, lo: int, hi: int) -> list[int]:
        """The matches found with ``lo <= seq < hi``, oldest first."""
        older, newer = self._older, self._newer
        found = list(reversed(older[bisect_right(older, -hi, key=neg) : bisect_right(older, -lo, key=neg)]))
        found += newer[bisect_left(newer, lo) : bisect_left(newer, hi)]
        return found

    def index(self, seq: int) -> int | None:
        """1-based place of match ``seq`` among all matches, when known (it is a match and
        every older record has been looked at); else None."""
        self._trim()
        if not self.older_done or not self.is_match(seq):
            return None
        older, newer = self._older, self._newer
        if newer and seq >= newer[0]:
            return len(older) + bisect_left(newer, seq) + 1
        return len(older) - bisect_left(older, -seq, key=neg)

    def is_match(self, seq: int) -> bool:
        """Whether ``seq`` is among the matches found."""
        older, newer = self._older, self._newer
        if newer and seq >= newer[0]:
            at = bisect_left(newer, seq)
            return at < len(newer) and newer[at] == seq
        at = bisect_left(older, -seq, key=neg)
        return at < len(older) and older[at] == seq

    def _first_from(self, bound: int) -> int | None:
        """The oldest match found at ``bound`` or newer."""
        older, newer = self._older, self._newer
        at_least = bisect_right(older, -bound, key=neg)  # older (descending) holds these first
        if at_least:
            return older[at_least - 1]
        at = bisect_left(newer, bound)
        return newer[at] if at < len(newer) else None

    def _last_before(self, bound: int) -> int | None:
        """The newest match found older than ``bound``."""
        older, newer = self._older, self._newer
        at = bisect_left(newer, bound)
        if at:
            return newer[at - 1]
        at_least = bisect_right(older, -bound, key=neg)
        return older[at_least] if at_least < len(older) else None

    def nearest(self, seq: int, *, forward: bool, inclusive: bool = False, limit: int | None = None) -> int | None:
        """The match nearest ``seq`` in that direction (``seq`` itself too when
        ``inclusive``), older than ``limit``; None when there is none; ``PENDING`` while
        the walk has not looked that far yet."""
        self._trim()
        if forward:
            bound = max(seq if inclusive else seq + 1, self.store.first_seq)
            if bound < self.down.at and not self.older_done:
                return PENDING  # records between ``seq`` and what was looked at
            found = self._first_from(bound)
            if found is not None:
                return found if limit is None or found < limit else None
            if self.newer_done or (limit is not None and self.up.at >= limit):
                return None
            return PENDING
        bound = seq + 1 if inclusive else seq
        if bound > self.up.at and not self.newer_done:
            return PENDING
        found = self._last_before(bound)
        if found is not None:
            return found
        return None if self.older_done else PENDING
