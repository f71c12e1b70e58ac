"""What a regular expression's shape allows a matcher to skip (read from Python's own parse).

- ``required_literal``: plain text every match contains, and how far matches reach around
  it: a fast ``in`` leaves few strings for the regex, searched only near that text.
- ``literal_alternatives``: the few strings a pattern matches when it matches nothing else
  (``time(out|d out)`` is ``timeout`` or ``timed out``): searching is then ``in`` alone.

Both read the parse of ``re`` itself (``re._parser``, ``sre_parse`` before 3.11): should a
Python change it, they answer "nothing to skip" and matching stays correct, only slower.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

try:
    from re import _parser as parser  # type: ignore[attr-defined]  # Python 3.11+
except ImportError:  # pragma: no cover - Python 3.10
    import sre_parse as parser

_MAX_WIDTH = 10_000
_CONTEXT_OPS = frozenset({"AT", "ASSERT", "ASSERT_NOT"})
#: At most this many strings stand for a pattern (``[0-9]{3}`` would be a thousand: no).
MAX_ALTERNATIVES = 16


@dataclass(frozen=True)
class RequiredLiteral:
    """Plain text every match of a regex contains, and where matches can lie around it.

    ``lead`` and ``tail``: at most how many characters a match holds before and after the
    text (None: unbounded, or, for ``tail``, a pattern whose answer depends on what lies
    outside the match: anchors, ``\\b``, lookarounds). ``fixed_lead``: every match holds
    exactly ``lead`` characters before the text, so a match containing the text at ``p``
    starts at ``p - lead`` (one ``match`` there instead of a search).
    """

    text: str = ""
    lead: int | None = None
    tail: int | None = None
    fixed_lead: bool = False


def _parse(pattern: re.Pattern[str]) -> Any:
    return parser.parse(pattern.pattern, pattern.flags & ~re.UNICODE)


def required_literal(pattern: re.Pattern[str]) -> RequiredLiteral:
    """The longest run of plain characters every match of ``pattern`` contains, if any."""
    try:
        parsed = _parse(pattern)
        items = list(parsed)
        best, best_start, run = "", 0, []
        for index, (op, argument) in enumerate([*items, (None, None)]):
            if str(op) == "LITERAL":
                run.append(chr(argument))
                continue
            if len(run) > len(best):
                best, best_start = "".join(run), index - len(run)
            run = []
        least_lead, lead = parser.SubPattern(parsed.state, items[:best_start]).getwidth()
        _, tail = parser.SubPattern(parsed.state, items[best_start + len(best) :]).getwidth()
        context = _uses_context(items)
    except Exception:  # a parser internal changed, a pattern nested too deep: no literal
        return RequiredLiteral()
    bounded_lead = lead < _MAX_WIDTH
    return RequiredLiteral(
        best,
        lead if bounded_lead else None,
        tail if tail < _MAX_WIDTH and not context else None,
        fixed_lead=bool(best) and bounded_lead and least_lead == lead,
    )


def literal_alternatives(pattern: re.Pattern[str]) -> tuple[str, ...] | None:
    """The strings ``pattern`` matches, when they are few and it matches only them anywhere:
    ``re.search(pattern, s)`` is then ``any(a in s for a in alternatives)``. None otherwise
    (anchors, classes of many characters, open repeats, flags inside the pattern)."""
    try:
        found = _strings(list(_parse(pattern)))
    except Exception:
        return None
    return tuple(sorted(found)) if found is not None else None


def _strings(items: list) -> set[str] | None:
    """Every string the sequence ``items`` matches, or None if they are many or unbounded."""
    strings = {""}
    for op, argument in items:
        name = str(op)
        if name == "LITERAL":
            choices: set[str] | None = {chr(argument)}
        elif name == "IN":
            choices = _class_chars(argument)
        elif name == "SUBPATTERN":
            _group, add_flags, del_flags, body = argument
            choices = _strings(list(body)) if not add_flags and not del_flags else None
        elif name == "BRANCH":
            choices = set()
            for branch in argument[1]:
                more = _strings(list(branch))
                if more is None:
                    return None
                choices |= more
        elif name in ("MAX_REPEAT", "MIN_REPEAT"):
            least, most, body = argument
            inner = _strings(list(body))
            if inner is None or most > 4:
                return None
            choices = set()
            for count in range(least, most + 1):
                layer = {""}
                for _ in range(count):
                    layer = {a + b for a in layer for b in inner}
                    if len(layer) > MAX_ALTERNATIVES:
                        return None
                choices |= layer
        else:
            return None
        if choices is None:
            return None
        strings = {a + b for a in strings for b in choices}
        if len(strings) > MAX_ALTERNATIVES:
            return None
    return strings


def _class_chars(items: list) -> set[str] | None:
    """The characters of a ``[...]`` class when it lists a few plainly."""
    chars: set[str] = set()
    for op, argument in items:
        name = str(op)
        if name == "LITERAL":
            chars.add(chr(argument))
        elif name == "RANGE" and argument[1] - argument[0] < MAX_ALTERNATIVES:
            chars.update(map(chr, range(argument[0], argument[1] + 1)))
        else:  # NEGATE, CATEGORY (\d, \w), a wide range
            return None
    return chars


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


_SAFE_CATEGORIES = frozenset({"CATEGORY_DIGIT", "CATEGORY_SPACE", "CATEGORY_WORD"})
_BOUNDARIES = frozenset({"AT_BOUNDARY", "AT_NON_BOUNDARY"})


@dataclass(frozen=True)
class RowSafety:
    """Whether a regex can be run on texts joined by NUL (``PackedTexts``) as on each alone.

    ``bounded``: searched between a text's start and end (``search(joined, start, end)``),
    it finds what it finds in that text alone: nothing looks before the text's start
    (``^``, ``\\A``, lookbehind) or past the match (lookahead; ``\\b`` and ``\\B`` see a NUL or
    the end, alike). ``nul_free`` besides: no match can hold a NUL, so a match in the joined
    texts lies inside one of them (``.``, ``[^...]``, ``\\D``, ``\\W``, ``\\S`` can hold one).
    """

    bounded: bool = False
    nul_free: bool = False


def row_safety(pattern: re.Pattern[str]) -> RowSafety:
    try:
        items = list(_parse(pattern))
        bounded, nul_free = _walk(items)
    except Exception:  # a parser internal changed, a pattern nested too deep: not safe
        return RowSafety()
    return RowSafety(bounded, bounded and nul_free)


def _walk(items: list) -> tuple[bool, bool]:
    """(only \\b / \\B look outside the match, no op can match a NUL) for parsed ``items``."""
    bounded = nul_free = True
    stack: list[Any] = [items]
    while stack:
        for op, argument in stack.pop():
            name = str(op)
            if name == "LITERAL":
                nul_free = nul_free and argument != 0
            elif name == "IN":
                nul_free = nul_free and _class_nul_free(argument)
            elif name in ("NOT_LITERAL", "ANY"):
                nul_free = False
            elif name == "AT":
                bounded = bounded and str(argument) in _BOUNDARIES
            elif name in ("SUBPATTERN",):
                stack.append(list(argument[3]))
            elif name in ("MAX_REPEAT", "MIN_REPEAT", "POSSESSIVE_REPEAT"):
                stack.append(list(argument[2]))
            elif name == "ATOMIC_GROUP":
                stack.append(list(argument))
            elif name == "BRANCH":
                stack.extend(list(branch) for branch in argument[1])
            elif name == "GROUPREF_EXISTS":
                stack.extend(list(part) for part in argument[1:] if part is not None)
            elif name != "GROUPREF":  # a backreference repeats text matched already
                return False, False  # lookarounds, and whatever this version adds
    return bounded, nul_free


def _class_nul_free(items: list) -> bool:
    for op, argument in items:
        name = str(op)
        if name == "LITERAL" and argument != 0:
            continue
        if name == "RANGE" and argument[0] > 0:
            continue
        if name == "CATEGORY" and str(argument) in _SAFE_CATEGORIES:
            continue
        return False  # NEGATE, NUL itself, other categories
    return True
