"""The log warehouse in tests: a chDB directory of the test's own (chDB opens one directory a
process at a time: every client a test opens is closed after it), records put in as
``console-tui ship`` puts them, rows put in as another collector would (SQL)."""

from __future__ import annotations

import gzip
import importlib.util
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager

import pytest

from console_tui.model.formats.otel_log import to_otel
from console_tui.model.store.record import LogRecord
from console_tui.warehouse.address import Address, parse_address
from console_tui.warehouse.clickhouse import TableClient
from console_tui.warehouse.otlp_encode import decode, encode
from console_tui.warehouse.schema import rows_of as rows_of_request
from console_tui.warehouse.spool import batch_token
from console_tui.warehouse.targets import TableTarget

STORE_MISSING = (
    ""
    if all(importlib.util.find_spec(name) for name in ("chdb", "clickhouse_connect", "opentelemetry"))
    else "the [store] extra (chdb, clickhouse-connect, opentelemetry-proto) is not installed"
)
needs_store = pytest.mark.skipif(bool(STORE_MISSING), reason=STORE_MISSING or "-")


@contextmanager
def table_client(address: Address) -> Iterator[TableClient]:
    client = TableClient(address, create=True)
    try:
        yield client
    finally:
        client.close()


def ship_records(
    address: Address,
    records: Sequence[LogRecord],
    *,
    host: str = "robot",
    batch: int = 5_000,
    client: TableClient | None = None,
) -> None:
    """Records into the table as ``console-tui ship`` sends them (the table made if missing);
    through ``client`` when given (chDB: the directory is open in one process at a time, and
    a client is that process)."""
    target = TableTarget(address)
    try:
        for start in range(0, len(records), batch):
            part = records[start : start + batch]
            data = gzip.compress(encode([to_otel(record, host=host) for record in part]))
            if client is not None:
                outcome = client.insert(rows_of_request(decode(gzip.decompress(data))), batch_token(data))
            else:
                outcome = target.send(data, len(part), batch_token(data))
            assert outcome.taken, outcome.problem
    finally:
        target.close()


def sql(address: Address, *statements: str) -> None:
    with table_client(address) as client:
        for statement in statements:
            client._client.command(statement)


def chdb_address(directory, table: str = "otel_logs") -> Address:
    return parse_address(f"chdb://{directory}?table={table}")


def rows_of(records: Iterable[LogRecord]) -> list[tuple]:
    """What a test compares of records: every field but the seq and the source."""
    return [(r.stamp_ns, r.level, r.node, r.msg, r.file, r.function, r.line, r.topics, r.robot) for r in records]
