"""The warehouse's source thread (chDB, the real engine): a first page, then older ones a
moment later (prefetched), so that rules changed at once are asked without a prefetch's
query before them; older pages asked for after that."""

from __future__ import annotations

from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import RuleSet
from console_tui.model.store.record import LogRecord
from console_tui.sources.warehouse_source import NEWEST, OLDER, WarehouseSource

from support.rosproc import wait_until
from support.warehouse import chdb_address, needs_store, ship_records

pytestmark = needs_store

T0 = 1_765_000_000_000_000_000


def fill(address) -> None:
    ship_records(address, [LogRecord(T0 + i * 1_000_000, [20, 30][i % 2], "n", f"m{i}") for i in range(400)])


def deliveries(source: WarehouseSource, until) -> list[tuple[int, str, int]]:
    """What the source delivered, (generation, kind, rows), until ``until(delivered)`` holds."""
    seen: list[tuple[int, str, int]] = []

    def more() -> bool:
        seen.extend((d.generation, d.kind, len(d.columns)) for d in source.take())
        return until(seen)

    assert wait_until(more), seen
    return seen


def test_rules_changed_at_once_wait_for_no_prefetch_and_prefetching_follows_a_moment_later(tmp_path):
    address = chdb_address(tmp_path)
    fill(address)
    source = WarehouseSource(address, first_rows=50, prefetch_rows=300, follow=False, prefetch_after_s=3600.0)
    source.start()
    try:
        first = deliveries(source, lambda seen: seen)
        assert first == [(1, NEWEST, 50)]
        source.ask(RuleSet().with_query(parse_query("level>=warn", utc=True)))
        assert deliveries(source, lambda seen: seen) == [(2, NEWEST, 50)]  # no older page of 1 before it
        source.prefetch_after_s = 0.0
        source.ask(RuleSet())
        later = deliveries(source, lambda seen: sum(rows for _, _, rows in seen) >= 300)
        assert later[0] == (3, NEWEST, 50) and {kind for _, kind, _ in later[1:]} == {OLDER}
        assert source.ask_older()  # past the prefetch: when asked
        assert deliveries(source, lambda seen: seen) == [(3, OLDER, 100)]
        assert source.at_start and not source.ask_older()
    finally:
        source.stop()
