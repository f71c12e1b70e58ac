"""How long an intake loop pauses after a turn (``sources.coalesce``), on an injected clock."""

from console_tui.sources import coalesce
from console_tui.sources.coalesce import Coalescer


class Clock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_a_full_turn_is_not_followed_by_a_pause():
    clock = Clock()
    coalescer = Coalescer(clock)
    clock.now += 1.0
    assert coalescer.after(coalesce.BELOW) == 0.0


def test_a_trickle_at_a_fast_rate_pauses_briefly():
    clock = Clock()
    coalescer = Coalescer(clock)
    clock.now += 0.002
    assert coalescer.after(40) == coalesce.FAST_S  # 20,000 a second


def test_a_trickle_at_a_slow_rate_pauses_longer():
    clock = Clock()
    coalescer = Coalescer(clock)
    clock.now += 0.010
    assert coalescer.after(50) == coalesce.SLOW_S  # 5,000 a second: a fleet's robot
    clock.now += 0.1
    assert coalescer.after(0) == coalesce.SLOW_S  # nothing: the wait timed out


def test_the_rate_is_measured_from_the_turn_before():
    clock = Clock()
    coalescer = Coalescer(clock)
    clock.now += 10.0
    assert coalescer.after(1) == coalesce.SLOW_S
    clock.now += 0.002
    assert coalescer.after(40) == coalesce.FAST_S
    assert coalescer.after(10) == coalesce.SLOW_S  # no time passed: not counted as fast
