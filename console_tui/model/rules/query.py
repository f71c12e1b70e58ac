"""The query line: a short text that compiles to rules.

    level>=warn node:nav* -node:rviz* "planner failed" /time(out|d out)/i file:planner.cpp

- Terms without a sign must all match for a row to be shown (together they become one
  inverted exclude rule: "exclude what does not match all of these").
- ``-term`` excludes rows that match it; ``+term`` highlights rows that match it. Each signed
  term is a rule of its own, so several ``-`` terms hide rows matching any of them and
  several ``+`` terms highlight rows matching any of them (rqt_console's panes).
- ``-( ... )`` and ``+( ... )`` group terms that must all match (a custom rule).
- Text: a bare word or a ``"quoted phrase"`` is looked for in the message, ignoring case
  unless it has a capital letter (smart case); ``/regex/`` is a regular expression, ``/regex/i``
  ignores case. ``msg:`` does the same explicitly.
- Keys: ``level:warn,error`` (a set), ``level>=warn`` (also ``>``, ``<=``, ``<``, ``=``);
  ``node:nav*,planner`` (names or globs; ``node:picker:/talker`` one robot's node); ``robot:picker,arm*`` (a fleet's robots, names or globs); ``file:`` and ``func:`` (text or ``/regex/``);
  ``line:120``; ``since:``, ``until:`` and ``time:FROM..TO`` (either end may be left out).
  Times: ``12:30``, ``12:30:05.250`` (today), ``2024-05-01T12:30``, ``2024-05-01``, seconds
  since the epoch (``1714566600.5``), or an age (``90s``, ``5m``, ``2h``, ``1d`` ago).

Errors are ``QueryError`` with ``position``, the index in the text where the problem is.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass
from datetime import date, datetime, timedelta, timezone, tzinfo

from ..levels import parse_severity
from ..timefmt import NS_PER_S
from .custom import CustomRule
from .location import LocationRule
from .message import MessageRule
from .node import NodeRule
from .pattern_match import TextMatch
from .robot import RobotRule
from .rule import Rule, RuleError
from .ruleset import Entry, Role
from .severity import SeverityRule
from .time_range import TimeRangeRule


class QueryError(RuleError):
    """A query that cannot be compiled; ``position`` is where in the text the problem is."""

    position: int

    def __init__(self, message: str, position: int) -> None:
        super().__init__(f"{message} (at {position + 1})", position)
        self.reason = message


def caret_line(text: str, error: QueryError) -> str:
    """The query text with a ``^`` under the error position, for showing inline."""
    return f"{text}\n{' ' * error.position}^ {error.reason}"


_KEYS = {
    "level": "level",
    "severity": "level",
    "sev": "level",
    "node": "node",
    "robot": "robot",
    "file": "file",
    "func": "function",
    "function": "function",
    "line": "line",
    "msg": "msg",
    "message": "msg",
    "time": "time",
    "since": "since",
    "until": "until",
}
_KEY_RE = re.compile(r"([A-Za-z]+)(>=|<=|:|=|>|<)")
_STOP = frozenset(" \t\n()")


@dataclass
class _Value:
    text: str
    start: int  # position of the value's first character in the query
    regex: bool = False
    ignore_case: bool = False
    quoted: bool = False


class _Parser:
    def __init__(self, text: str, now_ns: int, tz: tzinfo | None) -> None:
        self.text = text
        self.pos = 0
        self.now_ns = now_ns
        self.tz = tz

    # -- scanning -----------------------------------------------------------------------

    def skip_space(self) -> None:
        while self.pos < len(self.text) and self.text[self.pos].isspace():
            self.pos += 1

    def at_end(self) -> bool:
        self.skip_space()
        return self.pos >= len(self.text)

    def delimited(self, close: str, what: str) -> str:
        """Text up to the unescaped ``close`` (``\\`` escapes it and itself); pos after it."""
        start = self.pos - 1
        out = []
        text = self.text
        while self.pos < len(text):
            ch = text[self.pos]
            if ch == "\\" and self.pos + 1 < len(text) and text[self.pos + 1] in (close, "\\"):
                out.append(text[self.pos + 1] if close == '"' or text[self.pos + 1] == close else "\\\\")
                self.pos += 2
                continue
            if ch == close:
                self.pos += 1
                return "".join(out)
            out.append(ch)
            self.pos += 1
        raise QueryError(f"unterminated {what}", start)

    def value(self, *, names: bool = False) -> _Value:
        """A quoted text, a ``/regex/`` (not for ``names``: ROS names start with ``/``), or
        a word."""
        text, start = self.text, self.pos
        if start < len(text) and text[start] == '"':
            self.pos += 1
            return _Value(self.delimited('"', "quote"), start + 1, quoted=True)
        if start < len(text) and text[start] == "/" and not names:
            self.pos += 1
            pattern = self.delimited("/", "regular expression (no closing /)")
            flags_start = self.pos
            while self.pos < len(text) and text[self.pos] not in _STOP:
                self.pos += 1
            flags = text[flags_start : self.pos]
            if flags not in ("", "i"):
                raise QueryError(f"unknown regular expression flags {flags!r} (only i)", flags_start)
            return _Value(pattern, start + 1, regex=True, ignore_case=flags == "i")
        while self.pos < len(text) and text[self.pos] not in _STOP:
            self.pos += 1
        return _Value(text[start : self.pos], start)

    # -- grammar --------------------------------------------------------------------------

    def parse(self) -> tuple[Entry, ...]:
        required: list[Rule] = []
        entries: list[Entry] = []
        while not self.at_end():
            sign_at = self.pos
            sign = self.text[self.pos]
            if sign in "+-":
                self.pos += 1
                if self.at_end() or self.text[self.pos] == ")":
                    raise QueryError(f"expected a term after {sign!r}", sign_at)
                rules = self.group_or_term()
                rule = rules[0] if len(rules) == 1 else CustomRule(tuple(rules))
                entries.append(Entry(rule, Role.EXCLUDE if sign == "-" else Role.HIGHLIGHT))
            else:
                required.extend(self.group_or_term())
        if required:
            rule = required[0] if len(required) == 1 else CustomRule(tuple(required))
            entries.insert(0, Entry(rule, Role.EXCLUDE, inverted=True))
        return tuple(entries)

    def group_or_term(self) -> list[Rule]:
        self.skip_space()
        if self.text[self.pos] == ")":
            raise QueryError("unexpected ')'", self.pos)
        if self.text[self.pos] != "(":
            return [self.term()]
        opened = self.pos
        self.pos += 1
        parts: list[Rule] = []
        while True:
            if self.at_end():
                raise QueryError("unclosed '('", opened)
            ch = self.text[self.pos]
            if ch == ")":
                self.pos += 1
                break
            if ch in "(+-":
                raise QueryError(f"{ch!r} cannot be used inside a group", self.pos)
            parts.append(self.term())
        if not parts:
            raise QueryError("empty group", opened)
        return parts

    def term(self) -> Rule:
        start = self.pos
        key = _KEY_RE.match(self.text, self.pos)
        if key and key.group(1).lower() in _KEYS:
            self.pos = key.end()
            value = self.value(names=_KEYS[key.group(1).lower()] == "node")  # node:/talker is a name
            if value.text == "" and not value.quoted:
                raise QueryError(f"{key.group(1)}{key.group(2)} needs a value", self.pos)
            return self.keyed(_KEYS[key.group(1).lower()], key.group(2), value, start)
        if key and self.text.find("://", start, key.end() + 2) < 0:
            names = ", ".join(sorted(set(_KEYS) - {"severity", "function", "message", "sev"}))
            raise QueryError(f"unknown key {key.group(1)!r} (keys: {names}; quote text that has a colon)", start)
        return self.text_rule(self.value())

    def keyed(self, key: str, op: str, value: _Value, start: int) -> Rule:
        if op != ":" and op != "=" and key != "level":
            raise QueryError(f"{op!r} only works with level (use {key}:)", start)
        if key == "level":
            return self.level(op, value)
        if key == "msg":
            return self.text_rule(value)
        if key in ("file", "function"):
            return self.text_rule(value, field=key)
        if key == "node":
            names = [n for n in value.text.split(",") if n]
            if not names:
                raise QueryError("node: needs a name", value.start)
            return NodeRule(tuple(names))
        if key == "robot":
            names = [n for n in value.text.split(",") if n]
            if not names:
                raise QueryError("robot: needs a name", value.start)
            return RobotRule(tuple(names))
        if key == "line":
            if not value.text.isdigit():
                raise QueryError(f"line: expected a line number, got {value.text!r}", value.start)
            return LocationRule(line=int(value.text))
        if key == "since":
            return self.time_range(self.stamp(value.text, value.start), None, value.start)
        if key == "until":
            return self.time_range(None, self.stamp(value.text, value.start), value.start)
        low, dots, high = value.text.partition("..")
        if not dots:
            raise QueryError("time: expected FROM..TO (either may be left out)", value.start)
        if not low and not high:
            raise QueryError("time: give at least one end (FROM.. or ..TO)", value.start)
        end_at = value.start + len(low) + 2
        return self.time_range(
            self.stamp(low, value.start) if low else None,
            self.stamp(high, end_at) if high else None,
            value.start,
        )

    def text_rule(self, value: _Value, field: str | None = None) -> Rule:
        """The message's text, or with ``field`` the location's ``file`` or ``function``."""
        ignore_case = value.ignore_case if value.regex else value.text == value.text.lower()
        if value.regex:
            try:
                TextMatch(value.text, ignore_case, True)
            except RuleError as error:
                where = value.start + (error.position or 0)
                raise QueryError(error.message.split(": ", 1)[-1].rsplit(" at position", 1)[0], where) from None
        if field is None:
            return MessageRule(value.text, ignore_case, value.regex)
        if field == "file":
            return LocationRule(file=value.text, regex=value.regex, ignore_case=ignore_case)
        return LocationRule(function=value.text, regex=value.regex, ignore_case=ignore_case)

    def level(self, op: str, value: _Value) -> Rule:
        names = value.text.split(",")
        if op not in (":", "=") and len(names) > 1:
            raise QueryError(f"level{op} takes one level", value.start)
        levels = []
        at = value.start
        for name in names:
            try:
                levels.append(int(parse_severity(name)))
            except ValueError as error:
                raise QueryError(str(error), at) from None
            at += len(name) + 1
        if op in (":", "="):
            return SeverityRule(frozenset(levels))
        level = levels[0]
        if op == ">":
            level += 1
        elif op == "<":
            level -= 1
        rule = SeverityRule.at_least(level) if op.startswith(">") else SeverityRule.at_most(level)
        if rule.is_empty:
            raise QueryError(f"level{op}{value.text} matches no severity", value.start)
        return rule

    def time_range(self, start: int | None, end: int | None, at: int) -> Rule:
        try:
            return TimeRangeRule(start, end)
        except RuleError as error:
            raise QueryError(error.message, at) from None

    def stamp(self, text: str, at: int) -> int:
        """A time as nanoseconds since the epoch (see the module docstring for the forms)."""
        age = re.fullmatch(r"(\d+(?:\.\d+)?)(s|m|h|d)", text)
        if age:
            seconds = float(age.group(1)) * {"s": 1, "m": 60, "h": 3600, "d": 86400}[age.group(2)]
            return self.now_ns - int(seconds * NS_PER_S)
        if re.fullmatch(r"\d+(\.\d+)?", text):
            whole, _, fraction = text.partition(".")
            return int(whole) * NS_PER_S + int((fraction + "0" * 9)[:9])
        clock = re.fullmatch(r"(\d{1,2}):(\d{2})(?::(\d{2})(?:\.(\d{1,9}))?)?", text)
        try:
            if clock:
                hour, minute, second = int(clock.group(1)), int(clock.group(2)), int(clock.group(3) or 0)
                today = datetime.fromtimestamp(self.now_ns / NS_PER_S, self.tz or _local()).date()
                moment = datetime(today.year, today.month, today.day, hour, minute, second, tzinfo=self.tz or _local())
                return _ns(moment) + int(((clock.group(4) or "") + "0" * 9)[:9])
            moment = datetime.fromisoformat(text)
        except ValueError:
            raise QueryError(
                f"not a time: {text!r} (use 12:30, 12:30:05.2, 2024-05-01T12:30, epoch seconds or 5m)", at
            ) from None
        if isinstance(moment, date) and moment.tzinfo is None:
            moment = moment.replace(tzinfo=self.tz or _local())
        return _ns(moment)


def _local() -> tzinfo:
    return datetime.now().astimezone().tzinfo or timezone.utc


def _ns(moment: datetime) -> int:
    epoch = datetime(1970, 1, 1, tzinfo=timezone.utc)
    delta: timedelta = moment - epoch
    return (delta.days * 86400 + delta.seconds) * NS_PER_S + delta.microseconds * 1000


def parse_query(text: str, *, now_ns: int | None = None, utc: bool = False) -> tuple[Entry, ...]:
    """The entries a query compiles to (apply with ``RuleSet.with_query``); ``QueryError``.

    ``now_ns`` anchors ages and clock times (default: now); clock times are local unless ``utc``.
    """
    now = time.time_ns() if now_ns is None else now_ns
    return _Parser(text, now, timezone.utc if utc else None).parse()


def parse_time(text: str, *, now_ns: int | None = None, utc: bool = False) -> int:
    """One time as the query line reads it (``12:30``, ``2024-05-01T12:30``, epoch seconds,
    ``5m`` ago) in nanoseconds since the epoch; ``QueryError`` if it is none of those."""
    now = time.time_ns() if now_ns is None else now_ns
    return _Parser(text, now, timezone.utc if utc else None).stamp(text.strip(), 0)
