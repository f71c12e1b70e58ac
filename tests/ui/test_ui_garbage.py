"""What the screen leaves for Python's cycle collector: nothing of Textual's strips, so a
full collection (``ui/gc_policy.py``) has only live objects to visit (``textual_fixes``)."""

from __future__ import annotations

import gc

from rich.segment import Segment
from textual.strip import Strip

from console_tui.ui import textual_fixes

from support.feed import records
from support.ui import make_app, screen_text, until


def test_a_strip_cropped_or_divided_whole_is_freed_when_dropped():
    textual_fixes.apply()
    gc.collect()
    gc.disable()
    try:
        strip = Strip([Segment("a row of the table")])
        assert strip.crop_extend(0, strip.cell_length, None) is strip
        assert strip.divide([strip.cell_length]) == [strip]
        assert strip.crop_extend(0, 5, None).text == "a row"
        del strip
        left = gc.collect()
    finally:
        gc.enable()
    assert left == 0, "a dropped strip was left for the cycle collector"


async def test_drawing_the_table_leaves_no_strip_for_the_collector():
    app = make_app(200)
    async with app.run_test(size=(100, 24)) as pilot:
        await until(pilot, lambda: "200/200 shown" in screen_text(app), what="the records shown")
        gc.collect()
        gc.set_debug(gc.DEBUG_SAVEALL)
        try:
            for start in range(200, 1200, 100):
                app.main.intake.add_records(records(100, start=start))
                await pilot.press("up", "end")
                await pilot.pause()
            await until(pilot, lambda: "1,200/1,200 shown" in screen_text(app), what="the new records shown")
            gc.collect()
            strips = [item for item in gc.garbage if isinstance(item, Strip)]
        finally:
            gc.set_debug(0)
            gc.garbage.clear()
    assert strips == [], f"{len(strips)} strips drawn were freed only by the collector"


async def test_a_full_collection_runs_in_a_turn_of_its_own_after_the_drain():
    import asyncio

    from console_tui.ui.gc_policy import CollectionPolicy

    now = [0.0]
    policy = CollectionPolicy(clock=lambda: now[0], period=2.0, delay=0.01)
    policy.tick()
    assert policy.full_collections == 0, "collected before its period"
    now[0] = 2.5
    policy.tick()
    policy.tick()
    assert policy.full_collections == 0, "collected in the drain's turn"

    async def after_the_delay() -> None:
        """Until a callback the event loop runs after one the policy scheduled now would."""
        later = asyncio.Event()
        asyncio.get_running_loop().call_later(2 * policy.delay, later.set)
        await later.wait()

    await after_the_delay()
    assert policy.full_collections == 1, "not collected once, after the delay"
    policy.tick()
    await after_the_delay()
    assert policy.full_collections == 1, "collected again before the next period"


def test_what_is_alive_is_frozen_at_each_full_collection_until_start_up_settled():
    """Objects made after the first freeze (rclpy and modules imported by threads, the first
    screens' caches) are frozen by each full collection until ``settled`` seconds after
    start (the first one after that included), and never again."""
    import gc

    from console_tui.ui.gc_policy import CollectionPolicy

    now = [0.0]
    policy = CollectionPolicy(clock=lambda: now[0], settled=10.0)
    policy.started = 0.0  # as ``start`` sets it, without freezing this test process at start
    kept = []
    try:
        frozen = gc.get_freeze_count()
        now[0] = 5.0
        kept.append([object(), {}])  # made during start-up, alive for good
        policy.collect()
        assert not policy.refrozen and gc.get_freeze_count() > frozen, "not frozen while starting"
        frozen = gc.get_freeze_count()
        now[0] = 12.0
        kept.append([object(), {}])
        policy.collect()
        assert policy.refrozen and gc.get_freeze_count() > frozen
        again = gc.get_freeze_count()
        now[0] = 30.0
        kept.append([object(), {}])
        policy.collect()
        assert gc.get_freeze_count() == again, "frozen after start-up settled"
    finally:
        gc.unfreeze()
