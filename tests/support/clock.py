"""A clock for the code that works to a time budget (a refilter step, a search step): it moves
on by a fixed amount each time it is read, so what one step does is the same on a fast machine,
a slow one and a busy one."""

from __future__ import annotations


class TickingClock:
    """Seconds that grow by ``tick`` at every reading (``view.clock = TickingClock(0.001)``)."""

    def __init__(self, tick: float) -> None:
        self.tick = tick
        self.now = 0.0

    def __call__(self) -> float:
        self.now += self.tick
        return self.now
