"""The empty table says why it is empty: what the console waits for, or that rules hide all."""

from __future__ import annotations

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record_batch import RecordColumns
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp

from support.feed import StaticSource, records
from support.ui import line_with, make_app, screen_text, type_text, until


def in_table(app, text: str) -> bool:
    """Whether ``text`` shows inside the table's region."""
    region = app.main.table.region
    lines = screen_text(app).splitlines()[region.y : region.bottom]
    return any(text in line[region.x : region.right] for line in lines)


async def test_rules_hiding_everything_say_nothing_matches_and_how_many_are_hidden():
    app = make_app(100)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press("slash")
        await type_text(pilot, "node:nobody")
        await pilot.press("enter")
        hint = "nothing matches: 100 messages hidden by rules"
        await until(pilot, lambda: in_table(app, hint), what="the nothing-matches hint")
        await pilot.press("slash")
        await until(pilot, lambda: app.main.query_bar.is_open, what="the query line")
        for _ in "node:nobody":
            await pilot.press("backspace")
        await pilot.press("enter")
        await until(pilot, lambda: "100/100 shown" in screen_text(app), what="every row back")
        await until(pilot, lambda: not in_table(app, "nothing matches"), what="the hint to go")


async def test_a_live_source_with_no_publisher_yet_is_waited_for_on_screen():
    queue = IntakeQueue()
    status = SourceStatus(origin="ROS 2 domain 7", path="raw+cdr", running=True)
    source = StaticSource(status)
    app = ConsoleApp(store=LogStore(), queue=queue, sources=[source], utc=True)
    async with app.run_test(size=(80, 24)) as pilot:
        hint = "waiting for /rosout or /rosout_agg publishers on ROS 2 domain 7…"
        await until(pilot, lambda: in_table(app, hint), what="the waiting hint")
        source.status = SourceStatus(topic="/rosout", publishers=2, origin="ROS 2 domain 7", running=True)
        await until(
            pilot,
            lambda: in_table(app, "2 publishers of /rosout on ROS 2 domain 7: waiting for the first message…"),
            what="the publishers counted",
        )
        queue.put(RecordColumns.from_records(records(3)))
        await until(pilot, lambda: "3/3 shown" in screen_text(app), what="the rows")
        assert "waiting" not in line_with(app, "3/3 shown")[1] and not in_table(app, "waiting")


def test_the_hint_says_each_state_in_words():
    from console_tui.ui.widgets.status_bar import StatusFacts, empty_hint

    def hint(filtering: bool = False, **facts) -> str:
        return empty_hint(StatusFacts(**facts), filtering)

    assert hint(shown=3, total=3) == ""
    assert hint(total=5, paused=True) == ""
    assert hint(total=1) == "nothing matches: 1 message hidden by rules"
    assert hint(total=5, filtering=True) == "filtering…"
    assert hint() == ""  # no source, nothing loaded
    starting = SourceStatus(origin="ROS 2 domain 3", path="starting")
    assert hint(sources=[starting]) == "starting on ROS 2 domain 3…"
    master = SourceStatus(origin="ROS 1", problem="waiting for master at http://127.0.0.1:11311")
    assert hint(sources=[master]) == "waiting for master at http://127.0.0.1:11311"
    one = SourceStatus(topic="/rosout_agg", publishers=1)
    assert hint(sources=[one]) == "1 publisher of /rosout_agg: waiting for the first message…"
