"""OpenTelemetry log records as OTLP's protobuf message (``ExportLogsServiceRequest``), and back.

``encode`` groups the records by resource (node, robot, host) and scope (the logger), as an
SDK's exporter does, so a batch carries each node's resource once; ``decode`` reads any
sender's request (attribute values of every kind become text, as the ClickHouse exporter
stores them; an integer line number stays an integer). Both use ``opentelemetry-proto``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from ..model.formats.otel_log import LINE_KEY, OLD_LINE_KEY, OtelLog


def _proto() -> Any:
    try:
        from opentelemetry.proto.collector.logs.v1 import logs_service_pb2
    except ImportError as error:  # the [store] extra is missing
        raise ImportError(
            "the log warehouse needs the [store] extra: pip install 'console-tui[store]' "
            f"(opentelemetry-proto: {error})"
        ) from None
    return logs_service_pb2


def encode(logs: Sequence[OtelLog]) -> bytes:
    """One ``ExportLogsServiceRequest`` holding ``logs``, serialized."""
    request = _proto().ExportLogsServiceRequest()
    groups: dict[tuple[tuple[str, str], ...], dict[str, list[OtelLog]]] = {}
    for log in logs:
        group = tuple(sorted(log.resource.items()))
        groups.setdefault(group, {}).setdefault(log.scope_name, []).append(log)
    for resource, scopes in groups.items():
        resource_logs = request.resource_logs.add()
        attributes = resource_logs.resource.attributes
        for name, text in resource:
            attributes.add(key=name).value.string_value = text
        for scope_name, members in scopes.items():
            scope_logs = resource_logs.scope_logs.add()
            scope_logs.scope.name = scope_name
            records = scope_logs.log_records
            for log in members:
                record = records.add(
                    time_unix_nano=log.time_unix_nano,
                    observed_time_unix_nano=log.observed_unix_nano,
                    severity_number=log.severity_number,
                    severity_text=log.severity_text,
                )
                record.body.string_value = log.body
                add = record.attributes.add
                for key, value in log.attributes.items():
                    if isinstance(value, int):
                        add(key=key).value.int_value = value
                    else:
                        add(key=key).value.string_value = value
    data: bytes = request.SerializeToString()
    return data


def _text(value: Any) -> str | int:
    """An ``AnyValue`` as the ClickHouse exporter keeps it: text (an integer stays one here)."""
    kind = value.WhichOneof("value")
    if kind == "string_value":
        return str(value.string_value)
    if kind == "int_value":
        return int(value.int_value)
    if kind == "bool_value":
        return "true" if value.bool_value else "false"
    if kind == "double_value":
        return repr(float(value.double_value))
    if kind == "bytes_value":
        return bytes(value.bytes_value).hex()
    if kind is None:
        return ""
    from google.protobuf.json_format import MessageToJson

    return str(MessageToJson(value, indent=None))


def _attributes(pairs: Iterable[Any]) -> dict[str, str | int]:
    found: dict[str, str | int] = {}
    for pair in pairs:
        value = _text(pair.value)
        found[str(pair.key)] = value if isinstance(value, str) or pair.key in (LINE_KEY, OLD_LINE_KEY) else str(value)
    return found


def decode(data: bytes) -> list[OtelLog]:
    """The records of a serialized ``ExportLogsServiceRequest`` (``DecodeError`` if it is none)."""
    request = _proto().ExportLogsServiceRequest.FromString(data)
    logs: list[OtelLog] = []
    for resource_logs in request.resource_logs:
        resource = {key: str(value) for key, value in _attributes(resource_logs.resource.attributes).items()}
        for scope_logs in resource_logs.scope_logs:
            scope = str(scope_logs.scope.name)
            for record in scope_logs.log_records:
                body = _text(record.body)
                logs.append(
                    OtelLog(
                        int(record.time_unix_nano),
                        int(record.observed_time_unix_nano),
                        int(record.severity_number),
                        str(record.severity_text),
                        body if isinstance(body, str) else str(body),
                        resource,
                        scope,
                        _attributes(record.attributes),
                    )
                )
    return logs


def decode_error() -> type[Exception]:
    """The exception ``decode`` raises for bytes that are no request."""
    from google.protobuf.message import DecodeError

    error: type[Exception] = DecodeError
    return error
