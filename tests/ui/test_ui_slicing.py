"""Work in slices on the event loop (search, rules, seek, overview) lets what waited during a
long frame go before its next slice (``ui/slicing.py``)."""

from __future__ import annotations

import asyncio
import time

from console_tui.ui.slicing import pause_between_slices


async def test_a_slice_woken_late_lets_what_waited_with_it_go_first():
    """A long frame held the event loop while the work slept: a key that came meanwhile is
    handled before the next slice, which would lengthen that wait."""
    order: list[str] = []

    async def work() -> None:
        await pause_between_slices(0.001)
        order.append("slice")

    async def key() -> None:
        await asyncio.sleep(0.005)
        order.append("key")

    tasks = [asyncio.create_task(work()), asyncio.create_task(key())]
    await asyncio.sleep(0)  # both asleep
    time.sleep(0.03)  # the frame: both wakes come due meanwhile, the work's first
    await asyncio.gather(*tasks)
    assert order == ["key", "slice"]


async def test_a_slice_woken_on_time_goes_on_at_once():
    loop = asyncio.get_running_loop()
    began = loop.time()
    await pause_between_slices(0.001)
    assert loop.time() - began < 0.05
