"""A real ClickHouse server, when ``CLICKHOUSE_URL`` names one (``http://user:password@host:8123/db``;
``https://`` for TLS): the exporter's DDL made, records shipped and read back exactly, the rules
pushed down, a batch sent twice shown once. Skipped, and said, otherwise (no modern ClickHouse
server installs on these machines: the other tests run the same SQL on chDB)."""

from __future__ import annotations

import os
import secrets
from urllib.parse import urlsplit

import pytest

from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import RuleSet
from console_tui.model.rules.stream import StreamFilter
from console_tui.model.store.record import LogRecord
from console_tui.warehouse.address import parse_address
from console_tui.warehouse.pages import TablePages
from console_tui.warehouse.pushdown import where

from support.warehouse import needs_store, rows_of, ship_records, table_client

URL = os.environ.get("CLICKHOUSE_URL", "")
pytestmark = [
    needs_store,
    pytest.mark.skipif(not URL, reason="CLICKHOUSE_URL is not set (a ClickHouse server to test against)"),
]


def server_address(table: str):
    parts = urlsplit(URL)
    scheme = "clickhouses" if parts.scheme == "https" else "clickhouse"
    return parse_address(f"{scheme}://{parts.netloc}{parts.path or '/default'}?table={table}")


def test_shipped_read_back_and_filtered_on_a_server():
    address = server_address(f"console_tui_test_{secrets.token_hex(4)}")
    records = [
        LogRecord(
            1_765_000_000_000_000_000 + i,
            [20, 30, 40][i % 3],
            f"n{i % 4}",
            f"m {i}",
            "f.cpp",
            "fn",
            i,
            robot=f"r{i % 2}",
        )
        for i in range(500)
    ]
    try:
        ship_records(address, records)
        ship_records(address, records[:100])  # sent twice
        with table_client(address) as client:
            everything = TablePages(client).newest(10_000).records()
            assert rows_of(everything) == rows_of(records)
            rules = RuleSet().with_query(parse_query("robot:r1 level>=warn -node:n3"))
            sent = TablePages(client, where(rules)).newest(10_000).records()
            assert rows_of(sent) == rows_of(r for r, _ in StreamFilter(rules).filter(everything))
    finally:
        with table_client(address) as client:
            client._client.command(f"DROP TABLE IF EXISTS {client.table}")
