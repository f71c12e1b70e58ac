"""The log warehouse on the screen (chDB, the real engine): its newest rows with their robot and
node, a query that asks the warehouse again, older rows at the top, newer rows followed, and a
warehouse that does not answer said on the status line while the keys go on working."""

from __future__ import annotations

import pytest

from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.sources.warehouse_source import WarehouseSource
from console_tui.ui.app import ConsoleApp
from console_tui.warehouse.address import parse_address

from support.otlp_receiver import free_port
from support.ui import run_command, screen_text, table_rows, type_text, until
from support.warehouse import chdb_address, needs_store, ship_records

pytestmark = needs_store

T0 = 1_765_000_000_000_000_000


def fleet_records(count: int, start: int = 0) -> list[LogRecord]:
    robots = ["picker", "cart", "forklift"]
    return [
        LogRecord(
            T0 + (start + i) * 10_000_000,
            [20, 20, 30, 40][i % 4],
            f"nav.node{i % 2}",
            f"{robots[i % 3]} message {start + i}",
            "/src/nav.cpp",
            "plan",
            10 + i % 90,
            robot=robots[i % 3],
        )
        for i in range(count)
    ]


def warehouse_app(address, **options) -> tuple[ConsoleApp, WarehouseSource]:
    source = WarehouseSource(address, first_rows=60, page_rows=60, prefetch_rows=0, poll_s=0.2, **options)
    return ConsoleApp(store=LogStore(), sources=[source], utc=True), source


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_the_newest_rows_then_a_query_asked_of_the_warehouse_then_older_rows(tmp_path, size):
    address = chdb_address(tmp_path)
    ship_records(address, fleet_records(300))
    app, source = warehouse_app(address)
    async with app.run_test(size=size) as pilot:
        await until(pilot, lambda: "forklift message 299" in screen_text(app), what="the newest row")
        await until(pilot, lambda: "60/60 shown" in screen_text(app), what=lambda: screen_text(app).splitlines()[-2])
        screen = screen_text(app)
        assert "Robot" in screen and "nav.node1" in screen
        status = screen.splitlines()[-2]
        assert "chdb://…" in status and str(tmp_path)[-20:] in status
        source.first_rows = source.page_rows = 20  # of the 50 rows the query shows: 20 at a time
        await pilot.press("slash")
        await type_text(pilot, "robot:cart level>=warn")
        await pilot.press("enter")
        await until(
            pilot,
            lambda: source.generation == 2 and len(app.main.store) == 20,
            what=lambda: f"the query asked again ({source.generation}, {len(app.main.store)}, {source.status})",
        )
        await until(pilot, lambda: "cart message 298" in screen_text(app), what="the query's rows")
        rows = [line for _, line in table_rows(app).values()]
        assert rows and all("cart" in line and ("WARN" in line or "ERROR" in line) for line in rows)
        records = list(app.main.store)
        assert {(r.robot, r.level >= 30) for r in records} == {("cart", True)}  # SQL sent only those
        oldest = records[0].msg
        await pilot.press("home", "home")
        await until(pilot, lambda: len(app.main.store) > 20, what="older rows")
        assert app.main.store.get(app.main.table.cursor_seq).msg == oldest  # the cursor stayed on its row
        await run_command(pilot, "Older rows from the log warehouse")  # the palette asks as well
        await until(pilot, lambda: len(app.main.store) > 40, what="older rows from the palette")
        stamps = [r.stamp_ns for r in app.main.store]
        assert stamps == sorted(stamps)
        for _ in range(10):  # home, home again at the top: the page before it, until the oldest
            if source.at_start:
                break
            before = len(app.main.store)
            await pilot.press("home", "home")
            await until(pilot, lambda b=before: len(app.main.store) > b or source.at_start, what="an older page")
        await until(pilot, lambda: len(app.main.store) == 50, what=lambda: f"the window's rows ({len(app.main.store)})")
        assert source.at_start
        expected = [r.msg for r in fleet_records(300) if r.robot == "cart" and r.level >= 30]
        assert [r.msg for r in app.main.store] == expected


async def test_newer_rows_are_followed(tmp_path):
    address = chdb_address(tmp_path)
    ship_records(address, fleet_records(30))
    app, source = warehouse_app(address)
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "forklift message 29" in screen_text(app), what="the rows")
        source.stop()  # chDB: the directory is written by one process at a time; here, this one
        ship_records(address, fleet_records(5, start=30))
        follower = WarehouseSource(address, first_rows=60, poll_s=0.2)
        app.main.warehouse.warehouses = [follower]
        app.main.sources.append(follower)
        follower.start()
        await until(pilot, lambda: "picker message 33" in screen_text(app), what="the newer rows")


async def test_a_warehouse_that_does_not_answer_is_said_and_the_keys_work():
    address = parse_address(f"clickhouse://127.0.0.1:{free_port()}/logs")
    app, _ = warehouse_app(address)
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "the log warehouse at" in screen_text(app), what="the problem said")
        assert "Connection refused" in screen_text(app)
        await pilot.press("slash")
        await type_text(pilot, "level>=warn")
        await pilot.press("enter")
        await until(pilot, lambda: app.main.filtering.rules.active_rules(), what="the query applied")
        assert "Connection refused; asking again in" in screen_text(app)


async def test_older_rows_wait_while_a_records_details_are_open(tmp_path):
    """The details hold a record's seq (n and p step from it): rows put before it would move
    it, so they are placed once the table is shown again."""
    address = chdb_address(tmp_path)
    ship_records(address, fleet_records(120))
    app, source = warehouse_app(address)
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "forklift message 119" in screen_text(app), what="the newest row")
        await pilot.press("enter")
        await until(pilot, lambda: "Severity" in screen_text(app), what="the details")
        assert source.ask_older()  # as the prefetch would, while the details are open
        await until(pilot, lambda: source.loaded == 120 and not source._older_asked, what="the older page read")
        await pilot.press("p")
        await until(pilot, lambda: "cart message 118" in screen_text(app), what="the record before")
        assert len(app.main.store) == 60  # not placed yet
        await pilot.press("escape")
        await until(pilot, lambda: len(app.main.store) == 120, what="the older page placed")
        assert app.main.store.get(app.main.table.cursor_seq).msg == "cart message 118"
