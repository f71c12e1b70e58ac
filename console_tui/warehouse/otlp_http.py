"""Sending batches to an OpenTelemetry collector: OTLP over HTTP, protobuf, gzip.

One connection kept open between batches (``http.client``); each request bounded in time.
The answers, as OTLP's specification has them: 2xx taken (a partial success says how many
records were dropped), 429, 502, 503 and 504 (and a connection that fails) try again,
honouring ``Retry-After``; 413 sends smaller batches; 400 is a batch the collector will never
take (dropped and counted); any other answer (401, 403, 404: a wrong key or path) is tried
again later, so that a configuration put right loses nothing.
"""

from __future__ import annotations

import http.client
import os
import ssl
from collections.abc import Mapping
from urllib.parse import unquote, urlsplit

from .outcome import TAKEN, Outcome, retry_after_seconds

#: How long one request may take.
REQUEST_TIMEOUT_S = 30.0
#: The part of an answer read (an error text is shown, a success's body parsed).
MAX_ANSWER_BYTES = 1 << 20
_RETRIED = frozenset({408, 429, 502, 503, 504})


def parse_headers(text: str) -> dict[str, str]:
    """``OTEL_EXPORTER_OTLP_HEADERS``'s form: ``key1=value1,key2=value2`` (values URL-encoded)."""
    headers: dict[str, str] = {}
    for item in text.split(","):
        key, equals, value = item.partition("=")
        if equals and key.strip():
            headers[key.strip()] = unquote(value.strip())
    return headers


def environment_headers(environ: Mapping[str, str] | None = None) -> dict[str, str]:
    """The headers the standard variables give: ``OTEL_EXPORTER_OTLP_HEADERS``, then
    ``OTEL_EXPORTER_OTLP_LOGS_HEADERS`` (the more specific wins)."""
    env = os.environ if environ is None else environ
    headers = parse_headers(env.get("OTEL_EXPORTER_OTLP_HEADERS", ""))
    headers.update(parse_headers(env.get("OTEL_EXPORTER_OTLP_LOGS_HEADERS", "")))
    return headers


class OtlpSender:
    """POSTs gzipped ``ExportLogsServiceRequest`` bytes to ``url``."""

    def __init__(self, url: str, headers: Mapping[str, str] | None = None, *, timeout: float = REQUEST_TIMEOUT_S):
        parts = urlsplit(url)
        self.url = url
        self._secure = parts.scheme == "https"
        self._host = parts.hostname or ""
        self._port = parts.port
        self._path = parts.path + (f"?{parts.query}" if parts.query else "")
        self._timeout = timeout
        self._headers = {
            "Content-Type": "application/x-protobuf",
            "Content-Encoding": "gzip",
            "User-Agent": "console-tui-ship",
            **dict(headers or {}),
        }
        self._connection: http.client.HTTPConnection | None = None

    def _connect(self) -> http.client.HTTPConnection:
        if self._connection is None:
            if self._secure:
                self._connection = http.client.HTTPSConnection(
                    self._host, self._port, timeout=self._timeout, context=ssl.create_default_context()
                )
            else:
                self._connection = http.client.HTTPConnection(self._host, self._port, timeout=self._timeout)
        return self._connection

    def close(self) -> None:
        if self._connection is not None:
            self._connection.close()
            self._connection = None

    def send(self, body: bytes, records: int) -> Outcome:
        """Send one gzipped request of ``records`` records."""
        try:
            connection = self._connect()
            connection.request("POST", self._path, body=body, headers=self._headers)
            answer = connection.getresponse()
            status = answer.status
            content = answer.read(MAX_ANSWER_BYTES)
            retry_after = retry_after_seconds(answer.getheader("Retry-After"))
            if answer.getheader("Connection", "").lower() == "close":
                self.close()
        except (OSError, http.client.HTTPException) as error:
            self.close()
            return Outcome(False, retry=True, problem=f"{self._host}: {type(error).__name__}: {error}"[:300])
        if 200 <= status < 300:
            rejected, why = _partial_success(content)
            if rejected:
                return Outcome(True, rejected=min(rejected, records), problem=f"the collector dropped some: {why}")
            return TAKEN
        text = content[:200].decode("utf-8", "replace").strip()
        problem = f"HTTP {status}" + (f": {text}" if text else "")
        if status == 413:
            return Outcome(False, retry=True, problem=problem, too_large=True)
        if status == 400:
            return Outcome(False, problem=problem)
        return Outcome(False, retry=True, retry_after=retry_after if status in _RETRIED else None, problem=problem)


def _partial_success(content: bytes) -> tuple[int, str]:
    """(records rejected, the collector's message) of an ``ExportLogsServiceResponse``."""
    if not content:
        return 0, ""
    try:
        from opentelemetry.proto.collector.logs.v1.logs_service_pb2 import ExportLogsServiceResponse

        response = ExportLogsServiceResponse.FromString(content)
    except Exception:  # a body that is no response (JSON, text): the batch was taken
        return 0, ""
    partial = response.partial_success
    return int(partial.rejected_log_records), str(partial.error_message)[:200]
