"""How long an intake loop pauses after a turn, so that a turn pays for more than one message.

Both live intakes (ROS 2's wait-set loop, ROS 1's socket loop) take whatever is waiting in
one turn. A turn costs about the same for one message as for hundreds (a wait set rebuilt
and waited on, a queue hand-off), so when only a trickle arrives the loop pauses before the
next turn and lets messages gather:

- a full turn (``BELOW`` messages or more): no pause, the loop keeps up;
- a trickle while messages come at ``FAST_PER_S`` or more: ``FAST_S``, short, so what waits
  in the middleware's queue stays short (Fast DDS loses messages from a long one: see
  docs/decisions/0003-take-without-executor.md);
- a trickle slower than that (a fleet's robots each at a few thousand a second, a quiet
  robot): ``SLOW_S``. The intake process hands its batches to the app every 20 ms anyway
  (``intake_process.child.FLUSH_S``), so nothing shows later for it.
"""

from __future__ import annotations

import time
from collections.abc import Callable

BELOW = 64
FAST_S = 0.002
SLOW_S = 0.010
FAST_PER_S = 10_000


class Coalescer:
    """Call ``after(taken)`` once a turn has taken its messages; pause for what it returns."""

    def __init__(self, clock: Callable[[], float] = time.monotonic) -> None:
        self.clock = clock
        self._last = clock()

    def after(self, taken: int) -> float:
        """The pause after a turn that took ``taken`` messages (0: none)."""
        now = self.clock()
        since, self._last = now - self._last, now
        if taken >= BELOW:
            return 0.0
        return FAST_S if since > 0 and taken / since >= FAST_PER_S else SLOW_S
