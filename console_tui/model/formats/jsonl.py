"""JSON Lines: one JSON object per record with every field, lossless.

A line reads ``{"stamp_ns": 1700000000123456789, "level": 20, "node": "talker", "msg":
"hello", "file": "/src/talker.py", "function": "tick", "line": 42, "source": "run1.bag"}``;
ROS 1 records add ``"topics": "/rosout,/chatter"`` (left out when there are none), and a
fleet's records ``"robot": "picker"`` (left out when a record names no robot).
Newlines and quotes in text are JSON escapes, so every record is exactly one line. When
loaded, a record keeps the ``source`` it was saved with (the file's name if it had none).
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator
from typing import Any, BinaryIO

from ..levels import parse_severity
from ..store.record import LogRecord
from .line_format import TextFormat, TextFormatWriter
from .line_groups import TextLines
from .problems import Problems, RecordError

FIELDS = ("stamp_ns", "level", "node", "msg", "file", "function", "line", "source")
_INT_FIELDS = ("stamp_ns", "line")
_TEXT_FIELDS = ("node", "msg", "file", "function", "source", "topics", "robot")
_FLUSH_EVERY = 10_000


def record_to_json(record: LogRecord) -> str:
    """One record as one line of JSON (no newline)."""
    values = {name: getattr(record, name) for name in FIELDS}
    if record.topics:
        values["topics"] = record.topics
    if record.robot:
        values["robot"] = record.robot
    try:
        text = json.dumps(values, ensure_ascii=False, separators=(", ", ": "))
        text.encode("utf-8")
    except UnicodeEncodeError:  # lone surrogates: JSON escapes keep them exactly
        text = json.dumps(values, ensure_ascii=True, separators=(", ", ": "))
    return text


def record_from_json(values: Any, source: str) -> LogRecord:
    """A record from a decoded JSON object; raises RecordError naming the bad field."""
    if not isinstance(values, dict):
        raise RecordError(f"a JSON {type(values).__name__}, not an object")
    if "stamp_ns" not in values or "msg" not in values:
        raise RecordError("missing 'stamp_ns' or 'msg'")
    record = LogRecord(stamp_ns=0, level=20, node="", msg="", source=source)
    for name in _INT_FIELDS:
        if name in values:
            value = values[name]
            if not isinstance(value, int) or isinstance(value, bool):
                raise RecordError(f"{name!r} is not an integer: {value!r}")
            setattr(record, name, value)
    for name in _TEXT_FIELDS:
        if name in values and values[name] is not None:
            value = values[name]
            if not isinstance(value, str):
                raise RecordError(f"{name!r} is not text: {value!r}")
            setattr(record, name, value)
    if not record.source:
        record.source = source
    if "level" in values:
        record.level = _level(values["level"])
    return record


def _level(value: Any) -> int:
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    if isinstance(value, str):
        try:
            return int(parse_severity(value))
        except ValueError as error:
            raise RecordError(str(error)) from None
    raise RecordError(f"'level' is neither a number nor a name: {value!r}")


class JsonLinesWriter(TextFormatWriter):
    name = "jsonl"

    def write(self, records: Iterable[LogRecord], stream: BinaryIO) -> Iterator[int]:
        parts: list[str] = []
        count = 0
        for record in records:
            parts.append(record_to_json(record))
            count += 1
            if count % _FLUSH_EVERY == 0:
                stream.write(("\n".join(parts) + "\n").encode("utf-8"))
                parts.clear()
                yield count
        if parts:
            stream.write(("\n".join(parts) + "\n").encode("utf-8"))
        yield count


class JsonLinesFormat(TextFormat):
    name = "jsonl"
    title = "JSON Lines"

    def looks_like(self, first_line: str) -> bool:
        if not first_line.lstrip().startswith("{"):
            return False
        try:
            values = json.loads(first_line)
        except (ValueError, RecursionError):
            return False
        return isinstance(values, dict) and "stamp_ns" in values and "msg" in values

    def records(self, lines: TextLines, source: str, problems: Problems) -> Iterator[LogRecord]:
        decode = json.loads
        for number, text in lines:
            if not text.strip():
                continue
            try:
                values = decode(text)
            except ValueError as error:
                problems.add(f"not JSON: {error}", line=number)
                continue
            except RecursionError:
                problems.add("JSON nested too deeply to read (not a record of this format)", line=number)
                continue
            try:
                yield record_from_json(values, source)
            except RecordError as error:
                problems.add(str(error), line=number)
