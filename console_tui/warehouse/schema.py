"""The table ``otel_logs``: the OpenTelemetry Collector ClickHouse exporter's DDL, our rows
for it, and the SQL that reads a console record out of any row of it.

``create_table_sql`` is the exporter's own ``logs_table.sql`` (MergeTree, no TTL, as the
exporter makes it when no TTL is configured), so that ClickStack, HyperDX, Grafana's
ClickHouse plugin and a Collector writing beside us all read and write the same table.
``row_of`` is what the exporter inserts for an OpenTelemetry log record (attribute values as
text). ``RECORD_COLUMNS`` compute a record's fields in SQL exactly as
``model.formats.otel_log.from_otel`` does in Python: the rules go down into SQL on the same
expressions the rows are read with (``pushdown``).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from ..model.formats.otel_log import (
    FILE_KEY,
    FUNCTION_KEY,
    HOST_KEY,
    LINE_KEY,
    NAMESPACE_KEY,
    OLD_FILE_KEY,
    OLD_FUNCTION_KEY,
    OLD_LINE_KEY,
    OTEL_MAX,
    SEVERITY_TEXTS,
    TOPICS_KEY,
    UNSPECIFIED_LEVEL,
    OtelLog,
)

#: The exporter's ``logs_table.sql`` (opentelemetry-collector-contrib, exporter/clickhouseexporter).
_TABLE = """CREATE TABLE IF NOT EXISTS {database}.{table} (
    Timestamp DateTime64(9) CODEC(Delta(8), ZSTD(1)),
    TimestampTime DateTime DEFAULT toDateTime(Timestamp),
    TraceId String CODEC(ZSTD(1)),
    SpanId String CODEC(ZSTD(1)),
    TraceFlags UInt8,
    SeverityText LowCardinality(String) CODEC(ZSTD(1)),
    SeverityNumber UInt8,
    ServiceName LowCardinality(String) CODEC(ZSTD(1)),
    Body String CODEC(ZSTD(1)),
    ResourceSchemaUrl LowCardinality(String) CODEC(ZSTD(1)),
    ResourceAttributes Map(LowCardinality(String), String) CODEC(ZSTD(1)),
    ScopeSchemaUrl LowCardinality(String) CODEC(ZSTD(1)),
    ScopeName String CODEC(ZSTD(1)),
    ScopeVersion LowCardinality(String) CODEC(ZSTD(1)),
    ScopeAttributes Map(LowCardinality(String), String) CODEC(ZSTD(1)),
    LogAttributes Map(LowCardinality(String), String) CODEC(ZSTD(1)),
    EventName String CODEC(ZSTD(1)),

    INDEX idx_trace_id TraceId TYPE bloom_filter(0.001) GRANULARITY 1,
    INDEX idx_res_attr_key mapKeys(ResourceAttributes) TYPE bloom_filter(0.01) GRANULARITY 1,
    INDEX idx_res_attr_value mapValues(ResourceAttributes) TYPE bloom_filter(0.01) GRANULARITY 1,
    INDEX idx_scope_attr_key mapKeys(ScopeAttributes) TYPE bloom_filter(0.01) GRANULARITY 1,
    INDEX idx_scope_attr_value mapValues(ScopeAttributes) TYPE bloom_filter(0.01) GRANULARITY 1,
    INDEX idx_log_attr_key mapKeys(LogAttributes) TYPE bloom_filter(0.01) GRANULARITY 1,
    INDEX idx_log_attr_value mapValues(LogAttributes) TYPE bloom_filter(0.01) GRANULARITY 1,
    INDEX idx_body Body TYPE tokenbf_v1(32768, 3, 0) GRANULARITY 8
) ENGINE = MergeTree()
PARTITION BY toDate(TimestampTime)
PRIMARY KEY (ServiceName, TimestampTime)
ORDER BY (ServiceName, TimestampTime, Timestamp)
SETTINGS index_granularity = 8192, ttl_only_drop_parts = 1
"""

#: The columns a row is inserted with (the exporter's ``logs_insert.sql``; EventName left to its default).
INSERT_COLUMNS = (
    "Timestamp",
    "TraceId",
    "SpanId",
    "TraceFlags",
    "SeverityText",
    "SeverityNumber",
    "ServiceName",
    "Body",
    "ResourceSchemaUrl",
    "ResourceAttributes",
    "ScopeSchemaUrl",
    "ScopeName",
    "ScopeVersion",
    "ScopeAttributes",
    "LogAttributes",
)


def quoted(name: str) -> str:
    """An identifier (already checked to be a plain name by ``address``) quoted for SQL."""
    return "`" + name.replace("`", "") + "`"


def create_table_sql(database: str, table: str) -> str:
    return _TABLE.format(database=quoted(database), table=quoted(table))


def row_of(log: OtelLog) -> list[Any]:
    """The values of ``INSERT_COLUMNS`` for one record (``Timestamp`` as nanoseconds)."""
    service = log.resource.get("service.name", "")
    return [
        log.time_unix_nano or log.observed_unix_nano,
        "",
        "",
        0,
        log.severity_text,
        log.severity_number if 0 <= log.severity_number <= 255 else 0,
        service,
        log.body,
        "",
        log.resource,
        "",
        log.scope_name,
        "",
        {},
        {key: value if isinstance(value, str) else str(value) for key, value in log.attributes.items()},
    ]


def rows_of(logs: Sequence[OtelLog]) -> list[list[Any]]:
    return [row_of(log) for log in logs]


def sql_text(text: str) -> str:
    """A string literal (ClickHouse's escapes: backslash and quote)."""
    return "'" + text.replace("\\", "\\\\").replace("'", "\\'") + "'"


def _attribute(column: str, key: str) -> str:
    return f"{column}[{sql_text(key)}]"


def _first_of(column: str, *keys: str) -> str:
    values = [_attribute(column, key) for key in keys]
    expression = values[-1]
    for value in reversed(values[:-1]):
        expression = f"if({value} != '', {value}, {expression})"
    return expression


def _otel_number_of(level: str) -> str:
    """``otel_log.otel_number`` in SQL, of an Int32 expression."""
    bucket = f"least(greatest(intDiv({level}, 10) * 10, 10), 50)"
    return f"(intDiv({bucket} * 4, 10) + 1 + least(greatest(intDiv(({level} - {bucket}) * 4, 10), 0), 3))"


_DECIMAL = "match(SeverityText, '^[0-9]{1,3}$') AND toInt32OrZero(SeverityText) <= 255"
_EXACT = "toInt32OrZero(SeverityText)"
_NUMBER = "toInt32(SeverityNumber)"
_WORDS = ", ".join(sql_text(word) for word in SEVERITY_TEXTS)
_WORD_LEVELS = ", ".join(str(level) for level in SEVERITY_TEXTS.values())

#: ``otel_log.level_from_otel`` in SQL.
LEVEL = (
    "multiIf("
    f"{_NUMBER} BETWEEN 1 AND {OTEL_MAX} AND {_DECIMAL} AND {_otel_number_of(_EXACT)} = {_NUMBER}, {_EXACT}, "
    f"{_NUMBER} BETWEEN 1 AND 4, 10, "
    f"{_NUMBER} BETWEEN 5 AND {OTEL_MAX}, "
    f"intDiv({_NUMBER} - 5, 4) * 10 + 10 + intDiv(({_NUMBER} - 1) % 4 * 10, 4), "
    f"{_DECIMAL}, {_EXACT}, "
    f"toInt32(transform(upper(SeverityText), [{_WORDS}], [{_WORD_LEVELS}], {UNSPECIFIED_LEVEL})))"
)
STAMP = "toUnixTimestamp64Nano(Timestamp)"
NODE = "if(ServiceName != '', ServiceName, ScopeName)"
ROBOT = _first_of("ResourceAttributes", NAMESPACE_KEY, HOST_KEY)
FILE = _first_of("LogAttributes", FILE_KEY, OLD_FILE_KEY)
FUNCTION = _first_of("LogAttributes", FUNCTION_KEY, OLD_FUNCTION_KEY)
_LINE_TEXT = (
    f"if(mapContains(LogAttributes, {sql_text(LINE_KEY)}), "
    f"{_attribute('LogAttributes', LINE_KEY)}, {_attribute('LogAttributes', OLD_LINE_KEY)})"
)
LINE = (
    f"if(match({_LINE_TEXT}, '^[0-9]{{1,10}}$') AND toUInt64OrZero({_LINE_TEXT}) <= 4294967295, "
    f"toUInt32OrZero({_LINE_TEXT}), 0)"
)
TOPICS = _attribute("LogAttributes", TOPICS_KEY)
MSG = "Body"

#: The longest message read (characters); longer ones are cut, with ``…`` after.
MAX_MESSAGE_CHARS = 100_000
_READ_MSG = (
    f"if(lengthUTF8(Body) > {MAX_MESSAGE_CHARS}, concat(substringUTF8(toValidUTF8(Body), 1, {MAX_MESSAGE_CHARS}), '…'), "
    "toValidUTF8(Body))"
)


def _read_text(expression: str) -> str:
    """A short text read: valid UTF-8 (a bad byte becomes U+FFFD), at most 1,000 characters, repeated ones shared."""
    return f"toLowCardinality(substringUTF8(toValidUTF8({expression}), 1, 1000))"


#: A record's fields as SQL over a row: (field, expression), in the order they are selected;
#: then ``identity`` (a hash of what the row says: its time, severity, node, message, robot and
#: line; a row stored twice is one record) and
#: ``valid`` (0 for a row whose message was not UTF-8, repaired).
RECORD_COLUMNS: tuple[tuple[str, str], ...] = (
    ("stamp", STAMP),
    ("level", LEVEL),
    ("node", _read_text(NODE)),
    ("msg", _READ_MSG),
    ("file", _read_text(FILE)),
    ("function", _read_text(FUNCTION)),
    ("line", LINE),
    ("topics", _read_text(TOPICS)),
    ("robot", _read_text(ROBOT)),
    (
        "identity",
        f"cityHash64(Timestamp, SeverityNumber, SeverityText, ServiceName, Body, {ROBOT}, {LINE})",
    ),
    ("valid", "isValidUTF8(Body)"),
)
#: What the rules test, by field: the same expressions without the reading's conversions.
FIELDS = {"stamp": STAMP, "level": LEVEL, "node": NODE, "msg": MSG, "file": FILE, "function": FUNCTION}
FIELDS |= {"line": LINE, "robot": ROBOT}
