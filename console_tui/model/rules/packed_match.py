"""Text matches run on a chunk's messages as packed (``PackedTexts``): one string, all at once.

Testing messages one by one costs a Python-level step per message and first a ``str`` for
each (splitting the joined text). Where the match allows, these look for the text in the
joined messages with a few C-level calls instead (``str.split`` finds every occurrence)
and turn the few places found into rows (``bisect`` on the messages' starts):

- a substring: where it occurs; ignoring case, in the joined text lower-cased once (when
  it is all ASCII, where lower-casing keeps every position and equals case folding);
- a regex standing for a few strings (``literal_alternatives``): where any of them occurs;
- a regex with a plain text every match holds (``required_literal``): one anchored
  ``match`` at each occurrence less the fixed lead when no match can hold a NUL (so none
  runs from one message into the next), else a ``search`` of each message holding the
  text, bounded by its start and end (``RowSafety``).

A matcher answers ``None`` where it cannot help (text that is not ASCII while ignoring
case, a text found in most messages, a pattern that looks outside its match), and the
caller tests the messages one by one instead: the answers are the same either way.
"""

from __future__ import annotations

import re
from bisect import bisect_right
from collections import deque
from collections.abc import Callable, Iterable
from itertools import accumulate, compress, repeat
from operator import add, ge, sub

from ..store.packed_texts import PackedTexts
from .regex_shape import RequiredLiteral, RowSafety

#: ``matcher(texts, lo, hi)``: the mask over ``texts[lo:hi]``, or None to test them one by one.
PackedMatcher = Callable[[PackedTexts, int, int], "bytes | None"]

#: Occurrences of a text per message at most before testing them one by one is cheaper.
OCCURRENCES_PER_ROW = 0.25
#: For a regex (a ``match`` at each occurrence saves a ``search`` of each message).
REGEX_OCCURRENCES_PER_ROW = 2.0
_NUL = "\0"
_lowered: tuple[PackedTexts, str] | None = None


def lowered(texts: PackedTexts) -> str | None:
    """The joined text lower-cased, when it is ASCII (the last one kept: the rules testing
    a span share it); None otherwise."""
    global _lowered
    last = _lowered
    if last is not None and last[0] is texts:
        return last[1]
    if not texts.text.isascii():
        return None
    low = texts.text.lower()
    _lowered = (texts, low)
    return low


def occurrences(haystack: str, needle: str, texts: PackedTexts, lo: int, hi: int, per_row: float) -> list[int] | None:
    """Where ``needle`` (no NUL in it) starts in ``haystack`` (the joined text or its lower
    case) within the messages ``lo:hi``; None past ``per_row`` occurrences a message."""
    starts = texts.starts
    begin, end = starts[lo], starts[hi] - 1
    window = haystack if begin == 0 and end == len(haystack) else haystack[begin:end]
    limit = int((hi - lo) * per_row) + 1
    pieces = window.split(needle, limit)
    if len(pieces) > limit:
        return None
    del pieces[-1]
    size = len(needle)
    return list(accumulate(map(add, map(len, pieces), repeat(size)), initial=begin - size))[1:]


def rows_of(texts: PackedTexts, positions: Iterable[int], lo: int, hi: int) -> bytes:
    """The mask over ``lo:hi`` with a 1 for each message holding one of ``positions``."""
    mask = bytearray(hi - lo)
    rows = map(sub, map(bisect_right, repeat(texts.starts), positions), repeat(lo + 1))
    deque(map(mask.__setitem__, rows, repeat(1)), maxlen=0)
    return bytes(mask)


def substring_matcher(needle: str, ignore_case: bool) -> PackedMatcher | None:
    if not needle:
        return None
    if ignore_case:
        needle = needle.casefold()
    never = _NUL in needle or (ignore_case and not needle.isascii())  # no ASCII message holds it

    def matcher(texts: PackedTexts, lo: int, hi: int) -> bytes | None:
        if never:
            return None if ignore_case and not texts.text.isascii() else bytes(hi - lo)
        haystack = lowered(texts) if ignore_case else texts.text
        if haystack is None:
            return None
        found = occurrences(haystack, needle, texts, lo, hi, OCCURRENCES_PER_ROW)
        return None if found is None else rows_of(texts, found, lo, hi)

    return matcher


def alternatives_matcher(alternatives: tuple[str, ...], ignore_case: bool) -> PackedMatcher | None:
    """Any of ``alternatives`` (lower case already when ``ignore_case``)."""
    if not all(alternatives) or any(_NUL in text for text in alternatives):
        return None

    def matcher(texts: PackedTexts, lo: int, hi: int) -> bytes | None:
        haystack = lowered(texts) if ignore_case else texts.text
        if haystack is None:
            return None
        found: list[int] = []
        for text in alternatives:
            more = occurrences(haystack, text, texts, lo, hi, OCCURRENCES_PER_ROW)
            if more is None:
                return None
            found += more
        return rows_of(texts, found, lo, hi)

    return matcher


def literal_matcher(pattern: re.Pattern[str], literal: RequiredLiteral, safety: RowSafety) -> PackedMatcher | None:
    """Around the occurrences of ``literal`` (lower case already when ignoring case)."""
    text = literal.text
    if not text or _NUL in text or not safety.bounded:
        return None
    ignore_case = bool(pattern.flags & re.IGNORECASE)
    anchored = literal.fixed_lead and safety.nul_free and not _overlaps_itself(text)
    lead = literal.lead or 0
    match, search = pattern.match, pattern.search

    def matcher(texts: PackedTexts, lo: int, hi: int) -> bytes | None:
        haystack = lowered(texts) if ignore_case else texts.text
        if haystack is None:
            return None
        found = occurrences(haystack, text, texts, lo, hi, REGEX_OCCURRENCES_PER_ROW)
        if found is None:
            return None
        joined = texts.text
        if anchored:
            if found and found[0] < lead:  # no match starts before the text
                found = list(compress(found, map(ge, found, repeat(lead))))
            hits = map(match, repeat(joined), map(sub, found, repeat(lead)))
            return rows_of(texts, compress(found, hits), lo, hi)
        starts = texts.starts
        rows = sorted(set(map(sub, map(bisect_right, repeat(starts), found), repeat(1))))
        ends = map(sub, map(starts.__getitem__, map(add, rows, repeat(1))), repeat(1))
        hits = map(search, repeat(joined), map(starts.__getitem__, rows), ends)
        return rows_of(texts, map(starts.__getitem__, compress(rows, hits)), lo, hi)

    return matcher


def _overlaps_itself(text: str) -> bool:
    """Whether two occurrences of ``text`` can overlap (``str.split`` finds only one)."""
    return any(text[k:] == text[: len(text) - k] for k in range(1, len(text)))
