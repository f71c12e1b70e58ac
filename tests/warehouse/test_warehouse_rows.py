"""Records through the real engine (chDB): shipped into ``otel_logs`` with the exporter's DDL
and read back exactly; rows of other sources read sensibly; SQL's level is Python's; a window
read page by page, each row once."""

from __future__ import annotations

import itertools

import pytest

from console_tui.model.formats.otel_log import level_from_otel
from console_tui.model.store.record import LogRecord
from console_tui.warehouse.pages import LOOKBACK_NS, Abandoned, TablePages
from console_tui.warehouse.schema import LEVEL, create_table_sql

from support.warehouse import chdb_address, needs_store, rows_of, ship_records, sql, table_client

pytestmark = needs_store

T0 = 1_765_000_000_000_000_000


def records(count: int, *, start: int = 0, robot: str = "picker", step: int = 1_000_000) -> list[LogRecord]:
    return [
        LogRecord(
            T0 + (start + i) * step,
            [10, 20, 25, 30, 40, 50][i % 6],
            f"nav.node{i % 3}",
            f"message {start + i}" + ("\nsecond line" if i % 7 == 0 else ""),
            f"/src/file{i % 2}.cpp",
            "plan",
            i % 500,
            topics="/rosout,/cmd" if i % 5 == 0 else "",
            robot=robot,
        )
        for i in range(count)
    ]


def test_the_table_is_the_exporters_and_records_come_back_exactly(tmp_path):
    address = chdb_address(tmp_path)
    shipped = records(300)
    ship_records(address, shipped)
    with table_client(address) as client:
        ddl = client.value("SELECT create_table_query FROM system.tables WHERE name = 'otel_logs'")
        assert "ORDER BY (ServiceName, TimestampTime, Timestamp)" in ddl and "EventName" in ddl
        back = TablePages(client).newest(1_000)
    assert rows_of(back.records()) == rows_of(shipped)


def test_sql_reads_the_level_as_python_does(tmp_path):
    address = chdb_address(tmp_path)
    texts = ["", "TRACE", "debug", "Info", "WARNING", "err", "critical", "25", "31", "255", "256", "x", "ınfo", "0"]
    pairs = list(itertools.product(range(27), texts))
    with table_client(address) as client:
        client.create_table()
        values = ", ".join(
            f"(fromUnixTimestamp64Nano(toInt64({T0 + i})), {number}, '{text}')"
            for i, (number, text) in enumerate(pairs)
        )
        client._client.command(
            f"INSERT INTO default.otel_logs (Timestamp, SeverityNumber, SeverityText) VALUES {values}"
        )
        levels = client.columns(f"SELECT {LEVEL} FROM default.otel_logs ORDER BY Timestamp")[0]
    assert list(levels) == [level_from_otel(number, text) for number, text in pairs]


def test_another_collectors_rows_read_sensibly(tmp_path):
    address = chdb_address(tmp_path)
    sql(
        address,
        create_table_sql("default", "otel_logs"),
        "INSERT INTO default.otel_logs (Timestamp, SeverityText, SeverityNumber, ServiceName, Body, "
        "ResourceAttributes, ScopeName, LogAttributes) VALUES "
        f"(fromUnixTimestamp64Nano(toInt64({T0})), 'WARNING', 0, 'checkout', 'card declined', "
        "map('host.name', 'web-3'), 'app.pay', map('code.filepath', '/srv/pay.py', 'code.lineno', '88')), "
        f"(fromUnixTimestamp64Nano(toInt64({T0 + 1})), '', 0, '', unhex('ff41'), map(), 'lib', map())",
    )
    with table_client(address) as client:
        pages = TablePages(client)
        first, second = pages.newest(10).records()
    assert (first.level, first.node, first.robot, first.file, first.line) == (
        30,
        "checkout",
        "web-3",
        "/srv/pay.py",
        88,
    )
    assert (second.level, second.node, second.robot, second.msg) == (20, "lib", "", "\ufffdA")
    assert pages.repaired == 1


def test_a_window_read_backwards_and_forwards_each_row_once(tmp_path):
    address = chdb_address(tmp_path)
    shipped = records(1_000)
    ship_records(address, shipped)
    ship_records(address, shipped[400:500])  # a batch sent twice (a shipper killed after sending)
    with table_client(address) as client:
        pages = TablePages(client)
        newest = pages.newest(300)
        older = pages.older(300)
        rest = [pages.older(300) for _ in range(3)]
        assert pages.at_start
        backwards = [r for page in (*reversed(rest), older, newest) for r in page.records()]
        forward = TablePages(client)
        read = [forward.first(250)] + [forward.forward(250) for _ in range(5)]
        within = TablePages(client).first(100, within=150)
    assert rows_of(backwards) == rows_of(shipped)
    assert rows_of(r for page in read for r in page.records()) == rows_of(shipped)
    assert rows_of(within.records()) == rows_of(shipped[-150:-50])
    assert pages.duplicates == 100


def test_rows_at_one_time_across_a_page_edge_each_once(tmp_path):
    address = chdb_address(tmp_path)
    shipped = records(50, step=0) + records(50, start=50)  # 50 rows at one time, then 50 apart
    ship_records(address, shipped)
    with table_client(address) as client:
        pages = TablePages(client)
        pages_read = [pages.newest(70), pages.older(20), pages.older(20)]
    assert sorted(rows_of(r for page in pages_read for r in page.records())) == sorted(rows_of(shipped))


def test_following_finds_newer_rows_and_those_that_came_late(tmp_path):
    address = chdb_address(tmp_path)
    ship_records(address, records(100))
    with table_client(address) as client:
        pages = TablePages(client)
        pages.newest(1_000)
        assert not len(pages.newer(1_000))
        late = records(5, start=95, robot="cart")  # another robot's batch, behind the newest
        newer = records(10, start=100)
        ship_records(address, late + newer, client=client)
        found = pages.newer(1_000)
        assert rows_of(found.records()) == sorted(rows_of(late + newer))
        assert not len(pages.newer(1_000))
        too_late = records(1, start=100 - (LOOKBACK_NS // 1_000_000) - 5, robot="arm")
        ship_records(address, too_late, client=client)
        assert not len(pages.newer(1_000))  # beyond the lookback: found when the window is read again


def test_rows_the_rules_keep_far_back_are_found_without_asking_past_the_tables_oldest_row(tmp_path):
    address = chdb_address(tmp_path)
    hour = 3_600_000_000_000
    shipped = records(60, step=hour // 60)  # an hour, a row a minute: one in six FATAL
    ship_records(address, shipped)
    with table_client(address) as client:
        asked: list[str] = []
        columns = client.columns
        client.columns = lambda query: asked.append(query) or columns(query)  # type: ignore[method-assign]
        pages = TablePages(client, "SeverityNumber >= 21")
        fatal = pages.newest(20)
        assert pages.at_start
    assert rows_of(fatal.records()) == rows_of(r for r in shipped if r.level == 50)
    spans = [query for query in asked if "TimestampTime >=" in query and "LIMIT 1 OFFSET" in query]
    assert len(spans) == 2  # ten minutes, half an hour; then the table is shorter than the next


def test_a_page_is_given_up_between_its_queries_once_abandoned_says_so(tmp_path):
    address = chdb_address(tmp_path)
    ship_records(address, records(100))
    with table_client(address) as client:
        asked: list[str] = []
        columns = client.columns
        client.columns = lambda query: asked.append(query) or columns(query)  # type: ignore[method-assign]
        pages = TablePages(client, abandoned=lambda: len(asked) >= 2)  # new rules after the first query
        with pytest.raises(Abandoned):
            pages.newest(50)
    assert len(asked) == 2  # the table's extent, then the page's bound: its rows never asked
