"""A log record as an OpenTelemetry log record, and back (no network, no protobuf here).

Out (``console-tui ship``): ``to_otel(record, host=..., robot=...)`` gives an ``OtelLog``:

- ``Timestamp`` the ROS stamp, ``ObservedTimestamp`` when the shipper took the record in;
- ``SeverityNumber`` and ``SeverityText`` from the ROS level (``otel_severity``): DEBUG 5,
  INFO 9, WARN 13, ERROR 17, FATAL 21; a level between the steps (25) gets a number within
  its step's range (INFO3, 11) and its own number as the text ("25"), so it comes back exact;
- ``Body`` the message;
- resource ``service.name`` the node (the Node column: ROS 2's logger name, ROS 1's node
  name), ``service.namespace`` the robot, ``host.name`` the host;
- the instrumentation scope's name the logger's name (where OpenTelemetry's log bridges put
  a logger's name), and the attributes ``code.file.path``, ``code.function.name``,
  ``code.line.number`` (an integer) and, for ROS 1, ``ros.topics``.

In (``from_otel``), for records of any OpenTelemetry source, ours or not: the level from
``SeverityNumber`` (``level_from_otel``; TRACE counts as DEBUG), or from ``SeverityText``
when the number is unspecified (``WARNING``, ``CRITICAL``...); the node is ``service.name``,
else the scope's name; the robot ``service.namespace``, else ``host.name``; the location from
the ``code.*`` attributes, or their older names (``code.filepath``, ``code.function``,
``code.lineno``, which Python's OpenTelemetry logging handler writes). A record whose
``Timestamp`` is 0 takes its ``ObservedTimestamp`` (as the ClickHouse exporter does).

``warehouse.schema`` reads the ``otel_logs`` table with SQL that computes exactly these
fields (a test holds the two to each other).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from ..levels import severity_bucket, severity_name
from ..store.record import LogRecord
from ..store.record_batch import RecordColumns

#: OpenTelemetry's first SeverityNumber of each ROS severity's range (DEBUG 5..8, INFO 9..12 ...).
OTEL_BASE: dict[int, int] = {10: 5, 20: 9, 30: 13, 40: 17, 50: 21}
#: The highest SeverityNumber (FATAL4).
OTEL_MAX = 24
#: Severity words other OpenTelemetry sources write, with SeverityNumber 0, as ROS levels.
SEVERITY_TEXTS: dict[str, int] = {
    "TRACE": 10,
    "DEBUG": 10,
    "INFO": 20,
    "NOTICE": 20,
    "WARN": 30,
    "WARNING": 30,
    "ERROR": 40,
    "ERR": 40,
    "FATAL": 50,
    "CRITICAL": 50,
    "CRIT": 50,
    "ALERT": 50,
    "EMERG": 50,
    "EMERGENCY": 50,
    "PANIC": 50,
}
#: A record's level when neither its number nor its text says one.
UNSPECIFIED_LEVEL = 20

#: The attributes' keys (stable OpenTelemetry semantic conventions; ``ros.topics`` is ours).
FILE_KEY, FUNCTION_KEY, LINE_KEY = "code.file.path", "code.function.name", "code.line.number"
OLD_FILE_KEY, OLD_FUNCTION_KEY, OLD_LINE_KEY = "code.filepath", "code.function", "code.lineno"
TOPICS_KEY = "ros.topics"
SERVICE_KEY, NAMESPACE_KEY, HOST_KEY = "service.name", "service.namespace", "host.name"
_UINT32_MAX = 0xFFFFFFFF


@dataclass(slots=True)
class OtelLog:
    """One OpenTelemetry log record with its resource and scope, as plain values."""

    time_unix_nano: int
    observed_unix_nano: int
    severity_number: int
    severity_text: str
    body: str
    #: The resource's attributes (``service.name``, ``service.namespace``, ``host.name``).
    resource: dict[str, str] = field(default_factory=dict)
    scope_name: str = ""
    #: The record's attributes: strings, and ``code.line.number`` an integer.
    attributes: dict[str, str | int] = field(default_factory=dict)


def otel_number(level: int) -> int:
    """The SeverityNumber of a ROS level: its step's base, plus where it lies between steps."""
    bucket = int(severity_bucket(level))
    return OTEL_BASE[bucket] + min(max((level - bucket) * 4 // 10, 0), 3)


def otel_severity(level: int) -> tuple[int, str]:
    """(SeverityNumber, SeverityText) of a ROS level: ``WARN`` for 30, ``25`` for 25."""
    return otel_number(level), severity_name(level) if level in OTEL_BASE else str(level)


def _decimal(text: str) -> int | None:
    if 1 <= len(text) <= 3 and text.isascii() and text.isdigit():
        value = int(text)
        return value if value <= 255 else None
    return None


def level_from_otel(number: int, text: str) -> int:
    """The ROS level of an OpenTelemetry record's SeverityNumber and SeverityText.

    A decimal text (``25``) whose number is ours gives that level exactly; otherwise the number
    (1..24) its step's level and a part of the step (TRACE is DEBUG); with no number, a word of
    ``SEVERITY_TEXTS`` (ASCII, any case) or a decimal text; else INFO."""
    exact = _decimal(text)
    if 1 <= number <= OTEL_MAX:
        if exact is not None and otel_number(exact) == number:
            return exact
        if number < OTEL_BASE[10]:
            return 10
        bucket = ((number - OTEL_BASE[10]) // 4 + 1) * 10
        return bucket + (number - OTEL_BASE[bucket]) * 10 // 4
    if exact is not None:
        return exact
    if text.isascii():
        return SEVERITY_TEXTS.get(text.upper(), UNSPECIFIED_LEVEL)
    return UNSPECIFIED_LEVEL


def line_number(value: object) -> int:
    """A line number from an attribute: an integer, or a decimal text; 0 when it is neither
    (or past 32 bits)."""
    if isinstance(value, bool):
        return 0
    if isinstance(value, int):
        return value if 0 <= value <= _UINT32_MAX else 0
    if isinstance(value, str) and 0 < len(value) <= 10 and value.isascii() and value.isdigit():
        number = int(value)
        return number if number <= _UINT32_MAX else 0
    return 0


def to_otel(record: LogRecord, *, host: str, robot: str = "", observed_ns: int = 0) -> OtelLog:
    """``record`` as an OpenTelemetry log record; ``robot`` when the record names none."""
    number, text = otel_severity(record.level)
    resource = {SERVICE_KEY: record.node, HOST_KEY: host}
    namespace = record.robot or robot
    if namespace:
        resource[NAMESPACE_KEY] = namespace
    attributes: dict[str, str | int] = {}
    if record.file:
        attributes[FILE_KEY] = record.file
    if record.function:
        attributes[FUNCTION_KEY] = record.function
    if record.line or record.file:
        attributes[LINE_KEY] = record.line
    if record.topics:
        attributes[TOPICS_KEY] = record.topics
    return OtelLog(max(record.stamp_ns, 0), observed_ns, number, text, record.msg, resource, record.node, attributes)


def _text(attributes: Mapping[str, object], *keys: str) -> str:
    for key in keys:
        value = attributes.get(key)
        if value not in (None, ""):
            return value if isinstance(value, str) else str(value)
    return ""


def from_otel(log: OtelLog, *, source: str = "") -> LogRecord:
    """An OpenTelemetry log record (ours or any other source's) as a console record."""
    attributes, resource = log.attributes, log.resource
    line = attributes.get(LINE_KEY, attributes.get(OLD_LINE_KEY))
    return LogRecord(
        stamp_ns=log.time_unix_nano or log.observed_unix_nano,
        level=level_from_otel(log.severity_number, log.severity_text),
        node=_text(resource, SERVICE_KEY) or log.scope_name,
        msg=log.body,
        file=_text(attributes, FILE_KEY, OLD_FILE_KEY),
        function=_text(attributes, FUNCTION_KEY, OLD_FUNCTION_KEY),
        line=line_number(line),
        source=source,
        topics=_text(attributes, TOPICS_KEY),
        robot=_text(resource, NAMESPACE_KEY, HOST_KEY),
    )


def otel_logs_of(columns: RecordColumns, *, host: str, robot: str = "", observed_ns: int = 0) -> list[OtelLog]:
    """``to_otel`` for a batch in columns, without a ``LogRecord`` each (the shipper's path)."""
    robots = columns.robots if columns.robots is not None else [""] * len(columns)
    topics = columns.topics if columns.topics is not None else [""] * len(columns)
    resources: dict[tuple[str, str], dict[str, str]] = {}
    logs: list[OtelLog] = []
    append = logs.append
    for stamp, level, node, msg, file, function, line, record_topics, record_robot in zip(
        columns.stamps,
        columns.levels,
        columns.nodes,
        columns.msgs,
        columns.files,
        columns.functions,
        columns.lines,
        topics,
        robots,
        strict=True,
    ):
        namespace = record_robot or robot
        resource = resources.get((node, namespace))
        if resource is None:
            resource = resources[(node, namespace)] = {SERVICE_KEY: node, HOST_KEY: host}
            if namespace:
                resource[NAMESPACE_KEY] = namespace
        attributes: dict[str, str | int] = {}
        if file:
            attributes[FILE_KEY] = file
        if function:
            attributes[FUNCTION_KEY] = function
        if line or file:
            attributes[LINE_KEY] = line
        if record_topics:
            attributes[TOPICS_KEY] = record_topics
        number, text = _SEVERITIES.get(level) or otel_severity(level)
        append(OtelLog(max(stamp, 0), observed_ns, number, text, msg, resource, node, attributes))
    return logs


_SEVERITIES: dict[int, tuple[int, str]] = {level: otel_severity(level) for level in range(256)}
