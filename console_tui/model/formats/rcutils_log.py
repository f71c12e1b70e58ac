"""ROS 2 node log files: the lines rcutils formats (``~/.ros/log/<exe>_<pid>_<ms>.log``).

rcl's spdlog file sink writes each message as rcutils formats it, with
``RCUTILS_CONSOLE_OUTPUT_FORMAT`` (default ``[{severity}] [{time}] [{name}]: {message}``)
and a newline; a message with newlines in it spans several lines. A template is read
the way rcutils reads it (``rcutils/src/logging.c``): the tokens ``{severity} {name}
{message} {function_name} {file_name} {time} {date_time_with_ms} {time_as_nanoseconds}
{line_number}``; any other ``{...}`` is literal text; the escapes ``\\a \\b \\n \\r \\t``
and ``\\x1b`` are decoded. A record starts at a line that matches the template up to
``{message}``; the lines after it, up to the next such line, continue its message.
Colour codes (from captured console output) are ignored.
"""

from __future__ import annotations

import re
import time
from collections.abc import Iterator
from dataclasses import dataclass

from ..inert_text import strip_colour
from ..levels import SEVERITY_WORDS, Severity
from ..store.record import LogRecord
from .line_format import TextFormat
from .line_groups import LineGroup, LineKind, TextLines, group_lines, group_records
from .problems import Problems, RecordError

DEFAULT_TEMPLATE = "[{severity}] [{time}] [{name}]: {message}"

_SEVERITIES = SEVERITY_WORDS | {"UNSET": int(Severity.UNSET)}

#: token -> (pattern inside a record, pattern while finding where records start)
_TOKEN_PATTERNS: dict[str, str] = {
    "severity": r"DEBUG|INFO|WARN|ERROR|FATAL|UNSET",
    "name": r"[^\n]*?",
    "message": r".*?",
    "function_name": r"[^\n]*?",
    "file_name": r"[^\n]*?",
    "time": r"-?\d+\.\d{9}",
    "date_time_with_ms": r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{1,3}",
    "time_as_nanoseconds": r"-?\d+",
    "line_number": r"\d*",
}
#: The tokens rcutils knows in a format.
TOKENS: tuple[str, ...] = tuple(_TOKEN_PATTERNS)
_ESCAPES = {"a": "\a", "b": "\b", "n": "\n", "r": "\r", "t": "\t"}


def decode_template(template: str) -> str:
    """A format string with rcutils' escapes decoded (``\\n`` to a newline, ...)."""
    out: list[str] = []
    i = 0
    while i < len(template):
        char = template[i]
        if char == "\\" and template.startswith("x1b", i + 1):
            out.append("\x1b")
            i += 4
        elif char == "\\" and template[i + 1 : i + 2] in _ESCAPES:
            out.append(_ESCAPES[template[i + 1]])
            i += 2
        else:
            out.append(char)
            i += 1
    return "".join(out)


def split_template(template: str) -> list[tuple[bool, str]]:
    """The parts of a decoded template: ``(True, token)`` or ``(False, literal text)``."""
    parts: list[tuple[bool, str]] = []
    literal: list[str] = []
    i = 0
    while i < len(template):
        if template[i] == "{":
            end = template.find("}", i + 1)
            if end > i and template[i + 1 : end] in _TOKEN_PATTERNS:
                if literal:
                    parts.append((False, "".join(literal)))
                    literal = []
                parts.append((True, template[i + 1 : end]))
                i = end + 1
                continue
        literal.append(template[i])
        i += 1
    if literal:
        parts.append((False, "".join(literal)))
    return parts


@dataclass(frozen=True)
class LogLineTemplate:
    """A compiled ``RCUTILS_CONSOLE_OUTPUT_FORMAT``: a record regex and a start regex."""

    template: str
    record_re: re.Pattern[str]
    start_re: re.Pattern[str] | None
    end_re: re.Pattern[str] | None

    @classmethod
    def compile(cls, template: str) -> LogLineTemplate:
        parts = split_template(decode_template(template))
        seen: set[str] = set()
        pattern: list[str] = []
        for is_token, text in parts:
            if not is_token:
                pattern.append(re.escape(text))
            elif text in seen:
                pattern.append(f"(?:{_TOKEN_PATTERNS[text]})")
            else:
                seen.add(text)
                pattern.append(f"(?P<{text}>{_TOKEN_PATTERNS[text]})")
        record_re = re.compile(r"\A" + "".join(pattern) + r"\Z", re.DOTALL)
        head, tail = _head_and_tail(parts)
        start_re = re.compile(_line_pattern(head)) if head else None
        end_re = re.compile(_line_pattern(tail) + r"\Z") if tail and start_re is None else None
        return cls(template, record_re, start_re, end_re)

    def is_record_start(self, line: str) -> bool:
        if self.start_re is None:
            return True
        return self.start_re.match(strip_colour(line)) is not None


def _head_and_tail(parts: list[tuple[bool, str]]) -> tuple[list[tuple[bool, str]], list[tuple[bool, str]]]:
    """The template before ``{message}`` up to its first newline, and its last line after."""
    index = next((i for i, (is_token, text) in enumerate(parts) if is_token and text == "message"), len(parts))
    head: list[tuple[bool, str]] = []
    for is_token, text in parts[:index]:
        if not is_token and "\n" in text:
            head.append((False, text.split("\n", 1)[0]))
            break
        head.append((is_token, text))
    tail: list[tuple[bool, str]] = []
    for is_token, text in reversed(parts[index + 1 :]):
        if not is_token and "\n" in text:
            tail.insert(0, (False, text.rsplit("\n", 1)[1]))
            break
        tail.insert(0, (is_token, text))
    head = [part for part in head if part[0] or part[1]]
    tail = [part for part in tail if part[0] or part[1]]
    return head, tail


def _line_pattern(parts: list[tuple[bool, str]]) -> str:
    return "".join(re.escape(text) if not is_token else f"(?:{_TOKEN_PATTERNS[text]})" for is_token, text in parts)


def _date_to_ns(text: str) -> int:
    """``YYYY-mm-dd HH:MM:SS.mmm`` in local time (as rcutils writes it) to nanoseconds."""
    whole, _, millis = text.partition(".")
    seconds = time.mktime(time.strptime(whole, "%Y-%m-%d %H:%M:%S"))
    return int(seconds) * 1_000_000_000 + int(millis.ljust(3, "0")[:3]) * 1_000_000


def _stamp(fields: dict[str, str | None]) -> int:
    if fields.get("time_as_nanoseconds"):
        return int(fields["time_as_nanoseconds"] or 0)
    if fields.get("time"):
        seconds, _, nanos = (fields["time"] or "").partition(".")
        sign = -1 if seconds.startswith("-") else 1
        return sign * (abs(int(seconds)) * 1_000_000_000 + int(nanos))
    if fields.get("date_time_with_ms"):
        return _date_to_ns(fields["date_time_with_ms"] or "")
    return 0


class RcutilsLogFormat(TextFormat):
    """Node log files written through rcutils' output format (default or ``template``)."""

    name = "rcutils"
    title = "ROS 2 log file"

    def __init__(self, template: str = DEFAULT_TEMPLATE) -> None:
        self.template = LogLineTemplate.compile(template)

    def looks_like(self, first_line: str) -> bool:
        line = strip_colour(first_line)
        if self.template.start_re is not None:
            return self.template.start_re.match(line) is not None
        return self.template.record_re.match(line) is not None

    def records(self, lines: TextLines, source: str, problems: Problems) -> Iterator[LogRecord]:
        template = self.template
        if template.start_re is None and template.end_re is not None:
            groups = _groups_by_end(lines, template.end_re)
        else:
            start = template.start_re
            if start is None:
                classify = lambda line: LineKind.START  # noqa: E731
            else:
                match = start.match

                def classify(line: str) -> LineKind:
                    if match(line) is not None or ("\x1b" in line and match(strip_colour(line))):
                        return LineKind.START
                    return LineKind.MORE

            groups = group_lines(lines, classify, problems)
        return group_records(groups, lambda group: self.parse_record(group.text, source), problems, self.title)

    def parse_record(self, text: str, source: str) -> LogRecord:
        """One record's text (its lines joined by ``\\n``) as a record."""
        text = strip_colour(text)
        match = self.template.record_re.match(text)
        if match is None:
            raise RecordError(f"does not match the log format {self.template.template!r}: {text[:60]!r}")
        fields = match.groupdict()
        level = _SEVERITIES.get(fields.get("severity") or "", int(Severity.INFO))
        try:
            stamp_ns = _stamp(fields)
        except (ValueError, OverflowError) as error:
            raise RecordError(f"bad time: {error}") from None
        line_text = fields.get("line_number") or ""
        if len(line_text) > 12:
            raise RecordError(f"line number of {len(line_text)} digits")
        return LogRecord(
            stamp_ns=stamp_ns,
            level=level,
            node=fields.get("name") or "",
            msg=fields.get("message") or "",
            file=fields.get("file_name") or "",
            function=fields.get("function_name") or "",
            line=int(line_text) if line_text else 0,
            source=source,
        )


def _groups_by_end(lines: TextLines, end_re: re.Pattern[str]) -> Iterator[LineGroup]:
    """Records of a template that begins with ``{message}``: each ends at a line
    matching the template's last line."""
    group: LineGroup | None = None
    for number, text in lines:
        if group is None:
            group = LineGroup(number, [], True)
        group.lines.append(text)
        if end_re.search(strip_colour(text)):
            yield group
            group = None
    if group is not None:
        yield group
