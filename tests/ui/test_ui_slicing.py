"""Work in slices on the event loop (search, rules, seek, overview) lets what waited during a
long frame go before its next slice (``ui/slicing.py``)."""

from __future__ import annotations

import asyncio
import time
from types import SimpleNamespace

from console_tui.ui import slicing
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


class LoopClock:
    """The event loop's clock and sleep as ``pause_between_slices`` sees them: each sleep
    ends as long after the time asked as the next of ``late`` says (then on time)."""

    def __init__(self, *late: float) -> None:
        self.now = 0.0
        self.late = list(late)
        self.sleeps: list[float] = []

    def time(self) -> float:
        return self.now

    async def sleep(self, seconds: float) -> None:
        self.sleeps.append(seconds)
        self.now += seconds + (self.late.pop(0) if self.late else 0.0)


def pauses(monkeypatch, *late: float) -> list[float]:
    """The sleeps one ``pause_between_slices(1/60)`` takes when its wakes come ``late``."""
    clock = LoopClock(*late)
    monkeypatch.setattr(slicing, "asyncio", SimpleNamespace(get_running_loop=lambda: clock, sleep=clock.sleep))
    asyncio.run(pause_between_slices(1 / 60))
    return clock.sleeps


def test_a_slice_woken_on_time_goes_on_at_once(monkeypatch):
    assert pauses(monkeypatch) == [1 / 60]
    assert pauses(monkeypatch, slicing.LATE_S / 2) == [1 / 60]


def test_a_slice_woken_late_pauses_briefly_at_most_twice(monkeypatch):
    # Not the pause asked for again: after a 1/60 s pause that would be another 1/60 s.
    assert pauses(monkeypatch, 0.01) == [1 / 60, slicing.YIELD_S]
    assert pauses(monkeypatch, 0.01, 0.01, 0.01, 0.01) == [1 / 60] + [slicing.YIELD_S] * slicing.YIELDS
