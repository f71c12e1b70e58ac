"""Where ``console-tui ship`` sends a spooled batch: a collector (OTLP over HTTP) or the table
``otel_logs`` (ClickHouse, chDB). Each takes the batch as the spool keeps it (gzipped OTLP)."""

from __future__ import annotations

import gzip
import zlib
from collections.abc import Mapping
from typing import Protocol

from .address import OTLP, Address
from .clickhouse import TableClient, WarehouseError
from .otlp_encode import decode, decode_error
from .otlp_http import OtlpSender
from .outcome import Outcome
from .schema import rows_of


class Target(Protocol):
    """Sends one batch; ``close`` lets go of its connection."""

    def send(self, data: bytes, records: int, token: str) -> Outcome: ...

    def close(self) -> None: ...


class OtlpTarget:
    def __init__(self, address: Address, headers: Mapping[str, str]) -> None:
        self._sender = OtlpSender(address.target, headers)

    def send(self, data: bytes, records: int, token: str) -> Outcome:
        return self._sender.send(data, records)

    def close(self) -> None:
        self._sender.close()


class TableTarget:
    """Inserts a batch's records as the ClickHouse exporter would; the table is made (with
    the exporter's DDL) the first time it is reached."""

    def __init__(self, address: Address) -> None:
        self._address = address
        self._client: TableClient | None = None

    def send(self, data: bytes, records: int, token: str) -> Outcome:
        try:
            rows = rows_of(decode(gzip.decompress(data)))
        except (OSError, EOFError, zlib.error, decode_error()) as error:
            return Outcome(False, problem=f"a spooled batch is unreadable: {error}")
        try:
            if self._client is None:
                client = TableClient(self._address, create=True)
                try:
                    client.create_table()
                except WarehouseError:
                    client.close()
                    raise
                self._client = client
        except WarehouseError as error:
            return Outcome(False, retry=True, problem=str(error))
        outcome = self._client.insert(rows, token)
        if not outcome.taken:
            self.close()  # connect again for the next try
        return outcome

    def close(self) -> None:
        if self._client is not None:
            self._client.close()
            self._client = None


def open_target(address: Address, headers: Mapping[str, str] | None = None) -> Target:
    if address.kind == OTLP:
        return OtlpTarget(address, headers or {})
    return TableTarget(address)
