"""A live backlog (the loop was held up while messages came) is taken in a bounded part a
tick, so that no tick holds the keys up for long; the rest follows in the next ticks."""

from __future__ import annotations

from types import SimpleNamespace

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record_batch import RecordColumns
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp
from console_tui.ui.controllers.intake import MAX_LIVE_RECORDS_PER_TICK

from support.feed import records
from support.ui import screen_text, until


async def test_a_live_backlog_goes_in_at_most_the_live_cap_a_tick():
    queue = IntakeQueue()
    source = SimpleNamespace(
        status=SourceStatus(origin="ROS 2 domain 7", running=True), start=lambda: None, stop=lambda: None
    )
    app = ConsoleApp(store=LogStore(), queue=queue, sources=[source], utc=True)
    backlog = 2 * MAX_LIVE_RECORDS_PER_TICK + 100
    async with app.run_test(size=(100, 30)) as pilot:
        store = app.main.store
        before = store.end_seq
        queue.put(RecordColumns.from_records(records(backlog)))
        app.main.intake.drain_intake()  # one tick, with nothing else between
        assert store.end_seq - before == MAX_LIVE_RECORDS_PER_TICK
        await until(pilot, lambda: f"{backlog:,}/{backlog:,} shown" in screen_text(app), what="the rest")
