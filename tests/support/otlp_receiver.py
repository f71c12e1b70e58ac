"""A collector's far end for tests: an aiohttp server on loopback, in a thread of its own, that
decodes every OTLP/HTTP logs request with opentelemetry-proto (not console-tui's code) and
keeps what arrived; it can be told to refuse the next requests (503 with ``Retry-After``)."""

from __future__ import annotations

import asyncio
import gzip
import threading
import time
from dataclasses import dataclass

from aiohttp import web
from opentelemetry.proto.collector.logs.v1.logs_service_pb2 import ExportLogsServiceRequest, ExportLogsServiceResponse

from support.ros1 import own_port


@dataclass(frozen=True)
class Arrived:
    """One log record as it arrived."""

    time_unix_nano: int
    severity_number: int
    severity_text: str
    body: str
    resource: dict
    scope: str
    attributes: dict


def free_port() -> int:
    """A port of this worker's own (support.ros1.own_port: none the kernel hands out to others)."""
    return own_port()


def _value(any_value):
    kind = any_value.WhichOneof("value")
    return getattr(any_value, kind) if kind else None


class OtlpReceiver:
    def __init__(self, port: int | None = None, *, keep: bool = True) -> None:
        """``keep``: the records kept (else only counted, for a benchmark's millions)."""
        self.port = port or free_port()
        self.keep = keep
        self.counted = 0
        self.records: list[Arrived] = []
        self.requests: list[tuple[float, int]] = []  # (monotonic time, HTTP status answered)
        self._refuse: list[tuple[int, str | None]] = []
        #: Requests that came gzipped.
        self.gzipped = 0
        self._lock = threading.Lock()
        self._loop = asyncio.new_event_loop()
        self._ready = threading.Event()
        self._runner: web.AppRunner | None = None
        threading.Thread(target=self._serve, daemon=True).start()
        if not self._ready.wait(30):
            raise RuntimeError("the receiver did not start")

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def refuse(self, count: int, status: int = 503, retry_after: str | None = None) -> None:
        """Answer the next ``count`` requests with ``status`` (and ``Retry-After``)."""
        with self._lock:
            self._refuse.extend([(status, retry_after)] * count)

    def accept(self) -> None:
        """Take every request from now on."""
        with self._lock:
            self._refuse.clear()

    def _serve(self) -> None:
        asyncio.set_event_loop(self._loop)
        app = web.Application(client_max_size=64 << 20)
        app.router.add_post("/v1/logs", self._logs)
        self._runner = web.AppRunner(app)
        self._loop.run_until_complete(self._runner.setup())
        self._loop.run_until_complete(web.TCPSite(self._runner, "127.0.0.1", self.port).start())
        self._ready.set()
        self._loop.run_forever()

    async def _logs(self, request: web.Request) -> web.Response:
        body = await request.read()
        with self._lock:
            refusal = self._refuse.pop(0) if self._refuse else None
            if refusal is not None:
                self.requests.append((time.monotonic(), refusal[0]))
                headers = {"Retry-After": refusal[1]} if refusal[1] else {}
                return web.Response(status=refusal[0], headers=headers, text="busy")
        self.gzipped += request.headers.get("Content-Encoding") == "gzip"
        if body[:2] == b"\x1f\x8b":  # (aiohttp decompresses a gzipped body itself)
            body = gzip.decompress(body)
        message = ExportLogsServiceRequest.FromString(body)
        if not self.keep:
            counted = sum(len(s.log_records) for r in message.resource_logs for s in r.scope_logs)
            with self._lock:
                self.counted += counted
                self.requests.append((time.monotonic(), 200))
            return web.Response(body=b"", content_type="application/x-protobuf")
        arrived = []
        for resource_logs in message.resource_logs:
            resource = {kv.key: _value(kv.value) for kv in resource_logs.resource.attributes}
            for scope_logs in resource_logs.scope_logs:
                for log in scope_logs.log_records:
                    arrived.append(
                        Arrived(
                            log.time_unix_nano,
                            log.severity_number,
                            log.severity_text,
                            log.body.string_value,
                            resource,
                            scope_logs.scope.name,
                            {kv.key: _value(kv.value) for kv in log.attributes},
                        )
                    )
        with self._lock:
            self.records.extend(arrived)
            self.requests.append((time.monotonic(), 200))
        return web.Response(body=ExportLogsServiceResponse().SerializeToString(), content_type="application/x-protobuf")

    def count(self) -> int:
        with self._lock:
            return len(self.records) if self.keep else self.counted

    def bodies(self) -> list[str]:
        with self._lock:
            return [record.body for record in self.records]

    def close(self) -> None:
        if self._runner is not None:
            asyncio.run_coroutine_threadsafe(self._runner.cleanup(), self._loop).result(10)
        self._loop.call_soon_threadsafe(self._loop.stop)
