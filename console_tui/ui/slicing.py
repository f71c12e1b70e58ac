"""The pause between two slices of work done in the background on the event loop (the search,
the rules applied again, a jump's seek, the overview catching up).

A slice adds to whatever shares its turn of the loop. A task that sleeps is woken in the
turn after the one in which its time came; when a frame held the loop meanwhile, the slice
would run at once after it, before a key pressed during the frame or anything else that came
due later in that frame. So a pause that ends ``LATE_S`` late is followed by a short one
(``YIELD_S``), up to ``YIELDS`` in a row, so that what waited goes first; the pause asked for
is not taken again. The measurements behind it: docs/decisions/0016-background-work-in-slices.md.
"""

from __future__ import annotations

import asyncio

#: Woken this much later than asked: the loop was busy, and a short pause follows.
LATE_S = 0.002
YIELD_S = 0.001
YIELDS = 2


async def pause_between_slices(seconds: float) -> None:
    """Sleep ``seconds``, then ``YIELD_S`` while the last wake came ``LATE_S`` late (at most ``YIELDS`` times)."""
    loop = asyncio.get_running_loop()
    for _ in range(YIELDS + 1):
        asked = loop.time()
        await asyncio.sleep(seconds)
        if loop.time() - asked - seconds < LATE_S:
            return
        seconds = YIELD_S
