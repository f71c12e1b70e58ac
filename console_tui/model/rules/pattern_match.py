"""Text to look for in messages, file and function names: a substring or a regex, either case.

The one entry point for matching text a user typed against many strings (rules, the query
line, quick rules, search): ``TextMatch(text, ignore_case, regex)`` refuses a bad regex with
a ``RuleError`` (reason and position), and ``match.mask(strings)`` answers one byte per string
within a time limit, raising ``MatchTimeout`` past it: a catastrophic regex cannot freeze the
caller (``time_limit``: Python's ``re`` abandoned by a timer signal, on the main thread).
A caller that tests in pieces (the view) holds ``mask_function()`` and runs each piece
``with time_limit(...)``.

A regex runs only on strings that hold the plain text every match must contain
(``required_literal``), and only around it where the pattern allows.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace
from itertools import chain, compress, repeat
from operator import add, contains, is_, ne, sub

from .packed_match import PackedMatcher, alternatives_matcher, literal_matcher, substring_matcher
from .regex_shape import RequiredLiteral, literal_alternatives, required_literal, row_safety
from .rule import RuleError, mask_and, mask_not, mask_of_rows
from .time_limit import MatchTimeout, time_limit

__all__ = ["MATCH_LIMIT_S", "MatchTimeout", "RequiredLiteral", "TextMatch", "required_literal", "time_limit"]

#: How long one test of many strings may run before it is abandoned as too slow.
MATCH_LIMIT_S = 0.25


@dataclass(frozen=True)
class TextMatch:
    """Text to look for in a string: a substring, or a regex (``re.search``), either case."""

    text: str = ""
    ignore_case: bool = False
    regex: bool = False

    def __post_init__(self) -> None:
        if self.regex and self.text:
            self.pattern()  # raises RuleError now rather than while filtering

    @property
    def is_empty(self) -> bool:
        return self.text == ""

    def pattern(self) -> re.Pattern[str]:
        try:
            return re.compile(self.text, re.IGNORECASE if self.ignore_case else 0)
        except re.error as error:
            where = f" at position {error.pos}" if error.pos is not None else ""
            raise RuleError(f"invalid regular expression {self._shown()}: {error.msg}{where}", error.pos) from None
        except RecursionError:
            raise RuleError(f"invalid regular expression {self._shown()}: nested too deeply", None) from None
        except OverflowError as error:
            raise RuleError(f"invalid regular expression {self._shown()}: {error}", None) from None

    def _shown(self, limit: int = 80) -> str:
        """The text for a message: quoted, escapes visible (``repr``), cut to ``limit``."""
        return repr(self.text) if len(self.text) <= limit else repr(self.text[:limit]) + "…"

    def predicate(self) -> Callable[[str], bool]:
        """``str -> bool`` (for per-id lookups)."""
        if self.regex:
            search = self.pattern().search
            return lambda value: search(value) is not None
        if self.ignore_case:
            folded = self.text.casefold()
            return lambda value: folded in value.casefold()
        text = self.text
        return lambda value: text in value

    def mask_function(self) -> Callable[[list[str]], bytes]:
        """``strings -> mask``, the fastest way this kind of match allows."""
        if self.regex:
            return _RegexMasker(self.pattern())
        if self.ignore_case:
            needle = self.text.casefold()
            return lambda strings: bytes(map(contains, folded(strings), repeat(needle)))
        text = self.text
        return lambda strings: bytes(map(contains, strings, repeat(text)))

    def packed_matcher(self) -> PackedMatcher | None:
        """``(texts, lo, hi) -> mask or None`` over messages packed in one string, all at once
        (``packed_match``); None when this match cannot be run that way at all."""
        if not self.regex:
            return substring_matcher(self.text, self.ignore_case)
        if not self.text:
            return None
        pattern = self.pattern()
        masker = _RegexMasker(pattern)
        if masker.alternatives is not None:
            return alternatives_matcher(masker.alternatives, masker.ignore_case)
        return literal_matcher(pattern, masker.literal, row_safety(pattern))

    def mask(self, strings: list[str], limit_s: float = MATCH_LIMIT_S) -> bytes:
        """One byte per string, 1 where it matches; ``MatchTimeout`` after ``limit_s``."""
        with time_limit(limit_s):
            return self.mask_function()(strings)

    def describe(self) -> str:
        options = [name for name, on in (("regex", self.regex), ("ignore case", self.ignore_case)) if on]
        shown = f"/{self.text}/" if self.regex else repr(self.text)
        return shown + (f" ({', '.join(options)})" if options else "")


class _RegexMasker:
    """Regex masks, skipping what the pattern's shape allows (``regex_shape``):

    - a pattern that stands for a few strings is ``in`` tests alone;
    - otherwise, with a required literal, only strings that contain it are searched, and only
      around its occurrences; where every match holds a fixed number of characters before
      it, one ``match`` at the first occurrence answers most strings.

    Ignoring case, literals are looked for in lower-cased text (``folded``, shared by the
    rules testing the same strings), which is exact for ASCII literals in ASCII strings;
    other strings are searched whole.
    """

    __slots__ = ("alternatives", "ignore_case", "literal", "match", "search")

    def __init__(self, pattern: re.Pattern[str]) -> None:
        self.search = pattern.search
        self.match = pattern.match
        self.ignore_case = bool(pattern.flags & re.IGNORECASE)
        literal = required_literal(pattern)
        alternatives = literal_alternatives(pattern)
        if self.ignore_case:
            literal = replace(literal, text=literal.text.lower()) if literal.text.isascii() else RequiredLiteral()
            if alternatives is not None:
                alternatives = tuple({a.lower() for a in alternatives}) if all(map(str.isascii, alternatives)) else None
        self.literal = literal
        self.alternatives = alternatives

    def __call__(self, strings: list[str]) -> bytes:
        everything = range(len(strings))
        haystacks = strings
        usable: bytes | None = None  # which strings may use the literals (None: all)
        searched_whole: list[int] = []
        if self.ignore_case and (self.alternatives is not None or self.literal.text):
            haystacks, usable = folded(strings), ascii_only(strings)
            if usable.count(0):
                searched_whole = list(compress(everything, mask_not(usable)))
            else:
                usable = None
        if self.alternatives is not None:
            found: Iterable[int] = compress(everything, self._any_of(haystacks, usable))
        elif self.literal.text:
            found = self._around_literal(strings, haystacks, usable)
        else:
            return bytes(map(bool, map(self.search, strings)))
        whole = compress(searched_whole, map(self.search, map(strings.__getitem__, searched_whole)))
        return mask_of_rows(chain(found, whole), len(strings))

    def _any_of(self, haystacks: list[str], ascii_only: bytes | None) -> bytes:
        """Where any of the alternatives occurs (ASCII strings only, when ignoring case)."""
        alternatives = self.alternatives or ()
        hits = 0
        for text in alternatives:
            hits |= int.from_bytes(bytes(map(contains, haystacks, repeat(text))), "little")
        mask = hits.to_bytes(len(haystacks), "little")
        return mask if ascii_only is None else mask_and(mask, ascii_only)

    def _around_literal(self, strings: list[str], haystacks: list[str], usable: bytes | None) -> Iterable[int]:
        """The rows that match, among those whose haystack holds the literal."""
        literal, search = self.literal, self.search
        text = literal.text
        candidates = bytes(map(contains, haystacks, repeat(text)))
        if usable is not None:
            candidates = mask_and(candidates, usable)
        # C-level loops over the candidates (``map``), a Python one only over the few left.
        rows = list(compress(range(len(strings)), candidates))
        texts = list(map(strings.__getitem__, rows))
        hays = texts if haystacks is strings else list(map(haystacks.__getitem__, rows))
        firsts = list(map(str.find, hays, repeat(text)))
        if literal.fixed_lead:
            return self._at_occurrences(rows, texts, hays, firsts)
        starts: Iterable[int] = repeat(0) if literal.lead is None else map(sub, firsts, repeat(literal.lead))
        ends: Iterable[int] = repeat(sys.maxsize)
        if literal.tail is not None:
            lasts = map(str.rfind, hays, repeat(text))
            ends = map(add, lasts, repeat(len(text) + literal.tail))
        return compress(rows, map(search, texts, starts, ends))

    def _at_occurrences(self, rows: list[int], texts: list[str], hays: list[str], at: list[int]) -> list[int]:
        """Every match holds the literal right after ``lead`` characters: one ``match``
        (anchored, cheap) at each occurrence less the lead answers, the first occurrence
        for every row at once, then the next for the rows left, a few times; a row with
        still more occurrences is searched from there (a negative position counts as 0)."""
        text, lead, match = self.literal.text, self.literal.lead or 0, self.match
        found: list[int] = []
        pending = list(range(len(rows)))
        for _ in range(_OCCURRENCES_MATCHED):
            hits = bytes(map(bool, map(match, texts, map(sub, at, repeat(lead)))))
            found.extend(compress(pending, hits))
            misses = mask_not(hits)
            pending = list(compress(pending, misses))
            texts = list(compress(texts, misses))
            hays = list(compress(hays, misses))
            at = list(map(str.find, hays, repeat(text), map(add, compress(at, misses), repeat(1))))
            more = bytes(map(ne, at, repeat(-1)))
            pending, texts = list(compress(pending, more)), list(compress(texts, more))
            hays, at = list(compress(hays, more)), list(compress(at, more))
            if not pending:
                break
        else:
            found.extend(
                i for i, string, first in zip(pending, texts, at, strict=True) if self.search(string, first - lead)
            )
        return [rows[i] for i in sorted(found)]


#: Occurrences of the literal tried one ``match`` each, before a row is searched instead.
_OCCURRENCES_MATCHED = 3


class _SameStrings:
    """What is worked out once for the strings of a span, for every rule testing them in
    turn (the view tests each rule on a span one after the other): their case folding, and
    which are ASCII. Only the last strings are kept."""

    __slots__ = ("ascii_only", "folded", "strings")

    def __init__(self, strings: list[str]) -> None:
        self.strings = strings
        self.folded: list[str] | None = None
        self.ascii_only: bytes | None = None


_last: _SameStrings | None = None


def _about(strings: list[str]) -> _SameStrings:
    global _last
    last = _last
    if last is not None and len(last.strings) == len(strings) and all(map(is_, last.strings, strings)):
        return last
    _last = about = _SameStrings(strings)
    return about


def folded(strings: list[str]) -> list[str]:
    """``strings`` case-folded (``str.casefold``: ``größe`` is ``grösse``; for ASCII text the
    same as ``str.lower``), worked out once for the same strings."""
    about = _about(strings)
    if about.folded is None:
        about.folded = list(map(str.casefold, strings))
    return about.folded


def ascii_only(strings: list[str]) -> bytes:
    """1 for each ASCII string (where case folding keeps every character's position)."""
    about = _about(strings)
    if about.ascii_only is None:
        about.ascii_only = bytes(map(str.isascii, strings))
    return about.ascii_only
