"""Records as console lines, the way ROS prints log messages: for ``console-tui tail``.

A format may use the tokens of ROS 2's ``RCUTILS_CONSOLE_OUTPUT_FORMAT`` (``{severity}``,
``{name}``, ``{message}``, ``{time}``, ``{time_as_nanoseconds}``, ``{date_time_with_ms}``,
``{file_name}``, ``{function_name}``, ``{line_number}``; console-tui adds ``{robot}``, the
robot of a fleet a message came from) and those of ROS 1's
``ROSCONSOLE_FORMAT`` (``${severity}``, ``${time}``, ``${time:STRFTIME}``, ``${walltime}``,
``${node}``, ``${logger}``, ``${message}``, ``${file}``, ``${function}``, ``${line}``), in
any mix. As in rcutils, ``\\n``, ``\\t`` and the other escapes are decoded and any other
``{...}`` is plain text (``strict=False``, for ``$RCUTILS_CONSOLE_OUTPUT_FORMAT``, which
ROS prints that way); a format typed for us (``strict=True``) refuses an unknown ``{name}``,
as an unknown ``${...}`` always is (``TemplateError``).
``${node}`` and ``${logger}`` are both the logger name a message carries; ``${walltime}``
is its stamp too (a log message carries no other time). The default is ROS 2's:
``[{severity}] [{time}] [{name}]: {message}``.

Text from the message is made inert (``model.inert_text``): control characters, escape
sequences and bidi overrides show as visible stand-ins. A message's own line breaks and
tabs are kept, as ROS prints them.

With ``color``, a line is coloured by severity as rcutils colours it (DEBUG green,
WARN yellow, ERROR and FATAL red); while highlight rules are active, highlighted lines
are bold and the others dim.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from datetime import datetime, timezone

from ..inert_text import inert_json, multi_line, one_line
from ..levels import severity_level, severity_name
from ..store.record import LogRecord
from ..timefmt import split_stamp, stamp_text
from .jsonl import record_to_json
from .rcutils_log import DEFAULT_TEMPLATE, TOKENS, decode_template

_ROS1_TOKEN = re.compile(r"\$\{([A-Za-z_]+)(?::([^}]*))?\}")
_RCUTILS_TOKEN = re.compile(r"\{([A-Za-z_]+)\}")
ROS1_TOKENS = ("severity", "time", "walltime", "node", "logger", "message", "file", "function", "line")

_RESET = "\x1b[0m"
_DECORATIONS = {"highlight": "\x1b[1m", "dim": "\x1b[2m"}


class TemplateError(ValueError):
    """A format this module cannot print with; the text says why."""


Field = Callable[[LogRecord], str]


def _date_time_with_ms(utc: bool) -> Field:
    def field(record: LogRecord) -> str:
        sec, nsec = split_stamp(record.stamp_ns)
        moment = _moment(sec, utc)
        if moment is None:
            return stamp_text(record.stamp_ns)
        return f"{moment:%Y-%m-%d %H:%M:%S}.{nsec // 1_000_000:03d}"

    return field


def _strftime(pattern: str, utc: bool) -> Field:
    def field(record: LogRecord) -> str:
        moment = _moment(split_stamp(record.stamp_ns)[0], utc)
        return one_line(moment.strftime(pattern)) if moment is not None else stamp_text(record.stamp_ns)

    return field


def _moment(sec: int, utc: bool) -> datetime | None:
    try:
        moment = datetime.fromtimestamp(sec, tz=timezone.utc)
        return moment if utc else moment.astimezone()
    except (OverflowError, OSError, ValueError):
        return None


_FIELDS: dict[str, Field] = {
    "severity": lambda r: severity_name(r.level),
    "name": lambda r: one_line(r.node),
    "message": lambda r: multi_line(r.msg),
    "time": lambda r: stamp_text(r.stamp_ns),
    "time_as_nanoseconds": lambda r: str(r.stamp_ns),
    "file_name": lambda r: one_line(r.file),
    "function_name": lambda r: one_line(r.function),
    "line_number": lambda r: str(r.line),
    "robot": lambda r: one_line(r.robot),
}
#: A fleet's lines start with the robot (``console-tui tail --domain ...``).
ROBOT_PREFIX = "[{robot}] "
_ROS1_FIELDS = {
    "severity": "severity",
    "time": "time",
    "walltime": "time",
    "node": "name",
    "logger": "name",
    "message": "message",
    "file": "file_name",
    "function": "function_name",
    "line": "line_number",
}


class PrintFormat:
    """Prints records with one format (see the module docstring)."""

    def __init__(
        self, template: str | None = None, *, utc: bool = False, color: bool = False, strict: bool = False
    ) -> None:
        self.template = DEFAULT_TEMPLATE if template is None else template
        self.color = color
        self._parts = self._compile(decode_template(self.template), utc, strict)

    @staticmethod
    def _compile(template: str, utc: bool, strict: bool) -> list[str | Field]:
        parts: list[str | Field] = []
        literal: list[str] = []
        i = 0
        while i < len(template):
            ros1 = _ROS1_TOKEN.match(template, i) if template.startswith("${", i) else None
            if template.startswith("${", i) and ros1 is None:
                raise TemplateError(f"unfinished ${{...}} at {i + 1}: {template[i : i + 20]!r}")
            rcutils = _RCUTILS_TOKEN.match(template, i) if ros1 is None else None
            field: Field | None = None
            if ros1 is not None:
                name, argument = ros1.group(1), ros1.group(2)
                if name not in _ROS1_FIELDS:
                    known = ", ".join(f"${{{token}}}" for token in ROS1_TOKENS)
                    hint = " (not in a log message)" if name == "thread" else ""
                    raise TemplateError(f"unknown token ${{{name}}}{hint}: ROSCONSOLE_FORMAT tokens are {known}")
                if argument is not None and name in ("time", "walltime"):
                    field = _strftime(argument, utc)
                elif argument is not None:
                    raise TemplateError(f"${{{name}}} takes no ':{argument}'")
                else:
                    field = _FIELDS[_ROS1_FIELDS[name]]
                end = ros1.end()
            elif rcutils is not None and (rcutils.group(1) in TOKENS or rcutils.group(1) == "robot"):
                name = rcutils.group(1)
                field = _date_time_with_ms(utc) if name == "date_time_with_ms" else _FIELDS[name]
                end = rcutils.end()
            elif rcutils is not None and strict:
                raise TemplateError(_unknown_token(rcutils.group(1)))
            if field is None:
                literal.append(template[i])
                i += 1
                continue
            if literal:
                parts.append("".join(literal))
                literal = []
            parts.append(field)
            i = end
        if literal:
            parts.append("".join(literal))
        return parts

    def text(self, record: LogRecord, decoration: str | None = None) -> str:
        """The record's line (without the final newline); ``decoration`` is the rules'
        mark for it: "highlight", "dim" or None."""
        line = "".join(part if isinstance(part, str) else part(record) for part in self._parts)
        if not self.color:
            return line
        start = _DECORATIONS.get(decoration or "", "") + severity_level(record.level).ansi
        return f"{start}{line}{_RESET}" if start else line


def _unknown_token(name: str) -> str:
    """Why ``{name}`` is refused: the tokens there are, and the nearest one."""
    from difflib import get_close_matches

    known = (*TOKENS, *ROS1_TOKENS)
    near = get_close_matches(name.lower(), known, n=1)
    hint = f" (did you mean {{{near[0]}}}?)" if near and near[0] in TOKENS else ""
    hint = hint or (f" (did you mean ${{{near[0]}}}?)" if near else "")
    tokens = ", ".join(f"{{{token}}}" for token in TOKENS)
    return f"unknown token {{{name}}}{hint}: RCUTILS_CONSOLE_OUTPUT_FORMAT tokens are {tokens}"


def json_text(record: LogRecord) -> str:
    """The record as one line of JSON (console-tui's JSON Lines), with every character a
    terminal could act on written as a ``\\u`` escape."""
    return inert_json(record_to_json(record))
