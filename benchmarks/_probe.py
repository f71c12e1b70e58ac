"""What the benchmarks of the running app measure with: event-loop stalls and frames drawn."""

from __future__ import annotations

import asyncio
import time
from typing import Any


class StallProbe:
    """A task that sleeps 1 ms at a time; how late it wakes is how long the loop was busy."""

    def __init__(self) -> None:
        self.stalls: list[float] = []
        self._running = False
        self._task: asyncio.Task | None = None

    def start(self) -> None:
        self._running = True
        self._task = asyncio.create_task(self._run())

    async def _run(self) -> None:
        while self._running:
            before = time.perf_counter()
            await asyncio.sleep(0.001)
            self.stalls.append(time.perf_counter() - before - 0.001)

    async def stop(self) -> list[float]:
        self._running = False
        if self._task is not None:
            await self._task
        return self.stalls


def count_frames(widget: Any) -> list[float]:
    """Times at which ``widget`` is drawn from now on (its ``render_lines`` is wrapped)."""
    frames: list[float] = []
    original = widget.render_lines

    def counting_render_lines(crop):
        frames.append(time.perf_counter())
        return original(crop)

    widget.render_lines = counting_render_lines
    return frames
