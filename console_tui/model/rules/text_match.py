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
from operator import add, contains, sub

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
            folded = self.text.casefold()
            return lambda strings: bytes(map(contains, map(str.casefold, strings), repeat(folded)))
        text = self.text
        return lambda strings: bytes(map(contains, strings, repeat(text)))

    def mask(self, strings: list[str], limit_s: float = MATCH_LIMIT_S) -> bytes:
        """One byte per string, 1 where it matches; ``MatchTimeout`` after ``limit_s``."""
        with time_limit(limit_s):
            return self.mask_function()(strings)

    def describe(self) -> str:
        options = [name for name, on in (("regex", self.regex), ("ignore case", self.ignore_case)) if on]
        shown = f"/{self.text}/" if self.regex else repr(self.text)
        return shown + (f" ({', '.join(options)})" if options else "")


@dataclass(frozen=True)
class RequiredLiteral:
    """Plain text every match of a regex contains, and where matches can lie around it.

    ``lead`` and ``tail``: at most how many characters a match holds before and after the
    text (None: unbounded, or, for ``tail``, a pattern whose answer depends on what lies
    outside the match: anchors, ``\\b``, lookarounds).
    """

    text: str = ""
    lead: int | None = None
    tail: int | None = None


_MAX_WIDTH = 10_000
_CONTEXT_OPS = frozenset({"AT", "ASSERT", "ASSERT_NOT"})


def required_literal(pattern: re.Pattern[str]) -> RequiredLiteral:
    """The longest run of plain characters every match of ``pattern`` contains, if any.

    A fast ``in`` over many messages then leaves few for the regex, and those are searched
    only around the run's occurrences."""
    try:
        from re import _parser as parser  # Python 3.11+
    except ImportError:  # pragma: no cover - Python 3.10
        import sre_parse as parser  # type: ignore[no-redef]
    try:
        parsed = parser.parse(pattern.pattern, pattern.flags & ~re.UNICODE)
        items = list(parsed)
        best, best_start, run = "", 0, []
        for index, (op, argument) in enumerate([*items, (None, None)]):
            if str(op) == "LITERAL":
                run.append(chr(argument))
                continue
            if len(run) > len(best):
                best, best_start = "".join(run), index - len(run)
            run = []
        _, lead = parser.SubPattern(parsed.state, items[:best_start]).getwidth()
        _, tail = parser.SubPattern(parsed.state, items[best_start + len(best) :]).getwidth()
        context = _uses_context(items)
    except Exception:  # a parser internal changed, a pattern nested too deep: no literal
        return RequiredLiteral()
    return RequiredLiteral(
        best,
        lead if lead < _MAX_WIDTH else None,
        tail if tail < _MAX_WIDTH and not context else None,
    )


def _uses_context(items: list) -> bool:
    """Whether a parsed regex holds an op that looks outside the matched text (iterative:
    a pattern may nest deeper than Python's recursion limit allows)."""
    stack: list[object] = [items]
    while stack:
        node = stack.pop()
        if isinstance(node, tuple) and len(node) == 2 and str(node[0]) in _CONTEXT_OPS:
            return True
        if isinstance(node, (list, tuple)):
            stack.extend(node)
            continue
        data = getattr(node, "data", None)  # a SubPattern
        if isinstance(data, list):
            stack.append(data)
    return False


class _RegexMasker:
    """Regex masks. With a required literal, only strings that contain it are searched, and
    only around its occurrences (from the first one less the lead, to the last one plus the
    tail) where those are bounded.

    Ignoring case, the literal is looked for in lower-cased text, which is exact for an ASCII
    literal in ASCII text; other strings are searched whole, and a non-ASCII literal is not used.
    """

    __slots__ = ("_ignore_case", "_literal", "_search")

    def __init__(self, pattern: re.Pattern[str]) -> None:
        self._search = pattern.search
        self._ignore_case = bool(pattern.flags & re.IGNORECASE)
        literal = required_literal(pattern)
        if self._ignore_case:
            literal = replace(literal, text=literal.text.lower()) if literal.text.isascii() else RequiredLiteral()
        self._literal = literal

    def __call__(self, strings: list[str]) -> bytes:
        search, literal = self._search, self._literal
        text = literal.text
        if not text:
            return bytes(map(bool, map(search, strings)))
        everything = range(len(strings))
        searched_whole: list[int] = []
        if self._ignore_case:
            haystacks = list(map(str.lower, strings))
            ascii_only = bytes(map(str.isascii, strings))
            searched_whole = list(compress(everything, mask_not(ascii_only)))
            candidates = mask_and(bytes(map(contains, haystacks, repeat(text))), ascii_only)
        else:
            haystacks = strings
            candidates = bytes(map(contains, strings, repeat(text)))
        # C-level loops over the candidates (``map``), a Python one only over the matches.
        rows = list(compress(everything, candidates))
        starts: Iterable[int] = repeat(0)
        ends: Iterable[int] = repeat(sys.maxsize)
        if literal.lead is not None:
            firsts = map(str.find, map(haystacks.__getitem__, rows), repeat(text))
            starts = map(max, map(sub, firsts, repeat(literal.lead)), repeat(0))
        if literal.tail is not None:
            lasts = map(str.rfind, map(haystacks.__getitem__, rows), repeat(text))
            ends = map(add, lasts, repeat(len(text) + literal.tail))
        found = compress(rows, map(search, map(strings.__getitem__, rows), starts, ends))
        whole = compress(searched_whole, map(search, map(strings.__getitem__, searched_whole)))
        return mask_of_rows(chain(found, whole), len(strings))
