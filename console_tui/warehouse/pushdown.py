"""The rules in SQL: what the warehouse can leave out of an answer, so that it sends only rows
the rules may show.

The console applies every rule to every row it receives, as always; the SQL only narrows what
is sent, and must never leave out a row the rules would show. For each rule kind
``condition`` gives two SQL expressions over a row of ``otel_logs`` (on the expressions the
rows are read with, ``schema.FIELDS``):

- ``sure``: true only for rows the rule matches (a subset: ``0`` when nothing is sure);
- ``maybe``: true for every row the rule matches (a superset: ``1`` when anything may).

Where SQL says exactly what the rule does the two are one expression: the time, severity,
robot and node (names, and globs without ``[``), a line, text without case (ASCII text
ignoring case: exact on ASCII messages), regular expressions in the part of their syntax that
Python's ``re`` and ClickHouse's ``match`` (RE2) read alike. Otherwise ``maybe`` is a
necessary condition (a regex's required literal) or nothing. A row is shown when no exclude
entry matches it and, with "highlighted only", a highlight entry does: so ``where`` asks for
``NOT sure`` of each exclude entry, ``maybe`` of each inverted one (a query's terms), and with
"highlighted only" any highlight entry's ``maybe``. ``exact(rules)`` says whether the answer
is then exactly the rows shown.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass

from ..model.levels import MESSAGE_SEVERITIES
from ..model.loggers.logger_levels import split_robot
from ..model.rules.custom import CustomRule
from ..model.rules.location import LocationRule
from ..model.rules.message import MessageRule
from ..model.rules.node import is_glob, logger_name
from ..model.rules.pattern_match import TextMatch
from ..model.rules.regex_shape import required_literal
from ..model.rules.robot import RobotRule
from ..model.rules.rule import Rule, RuleError
from ..model.rules.ruleset import Entry, Role, RuleSet
from ..model.rules.severity import SeverityRule
from ..model.rules.time_range import TimeRangeRule
from .schema import FIELDS, sql_text

TRUE, FALSE = "1", "0"
#: The severity step of a row (``severity_bucket`` of its level): from the number when it has
#: one (its step holds the level whatever the text), else from the level the text gives.
BUCKET = (
    "if(SeverityNumber BETWEEN 1 AND 24, greatest(intDiv(toInt32(SeverityNumber) - 1, 4) * 10, 10), "
    f"least(greatest(intDiv({FIELDS['level']}, 10) * 10, 10), 50))"
)
#: DateTime64(9)'s range, in nanoseconds: times outside it are clamped to it.
_MIN_NS, _MAX_NS = -2_208_988_800_000_000_000, 9_223_372_036_854_775_807


@dataclass(frozen=True)
class Condition:
    sure: str
    maybe: str

    @property
    def exact(self) -> bool:
        return self.sure == self.maybe


NOTHING_SURE = Condition(FALSE, TRUE)


def _all(parts: Iterable[str]) -> str:
    kept = [part for part in parts if part != TRUE]
    if FALSE in kept:
        return FALSE
    return " AND ".join(f"({part})" for part in kept) if kept else TRUE


def _any(parts: Iterable[str]) -> str:
    kept = [part for part in parts if part != FALSE]
    if TRUE in kept:
        return TRUE
    return " OR ".join(f"({part})" for part in kept) if kept else FALSE


def _not(part: str) -> str:
    return FALSE if part == TRUE else TRUE if part == FALSE else f"NOT ({part})"


def _exact(sql: str) -> Condition:
    return Condition(sql, sql)


def _ascii(expression: str) -> str:
    return f"length({expression}) = lengthUTF8({expression})"


# -- text ------------------------------------------------------------------------------------------

#: What a regex may hold to mean the same to Python's ``re`` and to RE2: ASCII, escapes only of
#: punctuation (and \n, \t), no ``$`` (Python's matches before a final newline too), no ``(?``
#: but ``(?:``.
_RE2_SAFE = re.compile(r"(?:[^\\$(\x80-\U0010ffff]|\\[^A-Za-z0-9]|\\[nt]|\((?!\?)|\(\?:)*")
#: What the two read apart even so: POSIX classes (``[[:alpha:]]``), possessive repeats (``a*+``),
#: braces other than ``{m}``, ``{m,}`` and ``{m,n}`` under 1000.
_APART = re.compile(r"\[\[|\[:|[*+?}]\+|\{(?!\d{1,3}(?:,\d{0,3})?\})")


def re2_pattern(pattern: str, ignore_case: bool) -> str | None:
    """``pattern`` for ClickHouse's ``match``, meaning what it means to Python's ``re``; None
    when this module cannot say it does."""
    if not pattern.isascii() or not _RE2_SAFE.fullmatch(pattern) or _APART.search(pattern):
        return None
    try:
        re.compile(pattern)
    except re.error:
        return None
    # Python's "." stops at a newline; in ClickHouse's match it does not, unless told.
    return ("(?i)" if ignore_case else "") + "(?-s)" + pattern


def text_condition(expression: str, match: TextMatch) -> Condition:
    """``match`` (a substring or a regex, either case) over the text ``expression``."""
    text = match.text
    if not text:
        return Condition(FALSE, FALSE)
    if not match.regex:
        if not match.ignore_case:
            return _exact(f"position({expression}, {sql_text(text)}) > 0")
        if not text.isascii():
            return NOTHING_SURE
        found = f"positionCaseInsensitive({expression}, {sql_text(text)}) > 0"
        # Exact on ASCII text; Python's case folding may find more in other text.
        return Condition(found, _any([found, _not(_ascii(expression))]))
    try:
        pattern = match.pattern()
    except RuleError:
        return NOTHING_SURE
    literal = required_literal(pattern).text
    maybe = TRUE
    if literal:
        if not match.ignore_case:
            maybe = f"position({expression}, {sql_text(literal)}) > 0"
        elif literal.isascii():
            maybe = _any([f"positionCaseInsensitive({expression}, {sql_text(literal)}) > 0", _not(_ascii(expression))])
    re2 = re2_pattern(text, match.ignore_case)
    if re2 is None:
        return Condition(FALSE, maybe)
    found = f"match({expression}, {sql_text(re2)})"
    if not match.ignore_case:
        return _exact(found)
    return Condition(_all([found, _ascii(expression)]), _any([found, _not(_ascii(expression))]))


# -- names -----------------------------------------------------------------------------------------


def _like(glob: str) -> str | None:
    """A glob (``*``, ``?``) as a LIKE pattern; None for one with ``[`` (classes differ)."""
    if "[" in glob:
        return None
    escaped = glob.replace("\\", "\\\\").replace("%", "\\%").replace("_", "\\_")
    return escaped.replace("*", "%").replace("?", "_")


def names_condition(expression: str, names: Iterable[str]) -> Condition:
    """``names_predicate(names)`` over ``expression``: exact names and globs, case-sensitive."""
    names = list(dict.fromkeys(names))
    exact = [name for name in names if not is_glob(name)]
    parts: list[Condition] = []
    if exact:
        parts.append(_exact(f"{expression} IN ({', '.join(sql_text(name) for name in exact)})"))
    for glob in (name for name in names if is_glob(name)):
        like = _like(glob)
        parts.append(_exact(f"{expression} LIKE {sql_text(like)}") if like is not None else NOTHING_SURE)
    return Condition(_any(part.sure for part in parts), _any(part.maybe for part in parts))


def _node_condition(rule: Rule) -> Condition:
    names = getattr(rule, "names", ())
    parts: list[Condition] = []
    for name in names:
        robot, node = split_robot(name)
        nodes = names_condition(FIELDS["node"], dict.fromkeys((node, logger_name(node))))
        if not robot:
            parts.append(nodes)
            continue
        robots = names_condition(FIELDS["robot"], [robot])
        named = f"{FIELDS['robot']} != ''"
        parts.append(Condition(_all([named, robots.sure, nodes.sure]), _all([robots.maybe, nodes.maybe])))
    return Condition(_any(p.sure for p in parts), _any(p.maybe for p in parts))


def _time(start: int | None, end: int | None) -> Condition:
    parts = []
    if start is not None:
        start = min(max(start, _MIN_NS), _MAX_NS)
        parts.append(f"Timestamp >= fromUnixTimestamp64Nano(toInt64({start}))")
        parts.append(f"TimestampTime >= toDateTime({start // 1_000_000_000})")
    if end is not None:
        end = min(max(end, _MIN_NS), _MAX_NS)
        parts.append(f"Timestamp <= fromUnixTimestamp64Nano(toInt64({end}))")
        parts.append(f"TimestampTime <= toDateTime({end // 1_000_000_000})")
    return _exact(_all(parts))


def window_sql(since_ns: int | None, until_ns: int | None) -> str:
    """The window ``--since``/``--until`` chose, in SQL (``1``: all of it)."""
    return _time(since_ns, until_ns).sure


def condition(rule: Rule) -> Condition:
    """What SQL can say of ``rule`` (see the module's text)."""
    if rule.is_empty:
        return Condition(FALSE, FALSE)
    if isinstance(rule, SeverityRule):
        if rule.levels >= {int(s) for s in MESSAGE_SEVERITIES}:
            return _exact(TRUE)
        return _exact(f"{BUCKET} IN ({', '.join(str(level) for level in sorted(rule.levels))})")
    if isinstance(rule, TimeRangeRule):
        return _time(rule.start_ns, rule.end_ns)
    if isinstance(rule, RobotRule):
        robots = names_condition(FIELDS["robot"], rule.names)
        named = f"{FIELDS['robot']} != ''"
        return Condition(_all([named, robots.sure]), _all([named, robots.maybe]))
    if isinstance(rule, CustomRule):
        parts = [condition(part) for part in rule.parts if not part.is_empty]
        return Condition(_all(p.sure for p in parts), _all(p.maybe for p in parts))
    if isinstance(rule, MessageRule):
        return text_condition(FIELDS["msg"], rule.match)
    if isinstance(rule, LocationRule):
        parts = []
        for field, text in (("file", rule.file), ("function", rule.function)):
            if text:
                parts.append(text_condition(FIELDS[field], TextMatch(text, rule.ignore_case, rule.regex)))
        if rule.line is not None:
            parts.append(_exact(f"{FIELDS['line']} = {int(rule.line)}"))
        return Condition(_all(p.sure for p in parts), _all(p.maybe for p in parts))
    if rule.kind == "node":
        return _node_condition(rule)
    return NOTHING_SURE


def _entry(entry: Entry) -> Condition:
    found = condition(entry.rule)
    if entry.inverted:  # it matches what its rule does not
        return Condition(_not(found.maybe), _not(found.sure))
    return found


def where(rules: RuleSet) -> str:
    """A SQL condition true for every row ``rules`` may show (``1`` when it says nothing)."""
    parts = [_not(_entry(entry).sure) for entry in rules.active(Role.EXCLUDE)]
    highlights = rules.active(Role.HIGHLIGHT)
    if rules.highlighted_only and highlights:
        parts.append(_any(_entry(entry).maybe for entry in highlights))
    return _all(parts)


def exact(rules: RuleSet) -> bool:
    """Whether ``where(rules)`` holds for exactly the rows ``rules`` show."""
    entries = rules.active(Role.EXCLUDE)
    if rules.highlighted_only and rules.active(Role.HIGHLIGHT):
        entries = entries + rules.active(Role.HIGHLIGHT)
    return all(_entry(entry).exact for entry in entries)
