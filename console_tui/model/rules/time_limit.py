"""Abandoning text matching that runs too long.

``time_limit(seconds)`` arms a one-shot real-time timer (``SIGALRM``) around the code inside it:
past ``seconds`` that code is abandoned with ``MatchTimeout``, wherever it is, a catastrophic
``re.search`` included (Python's regex engine checks for pending signals every 4,096 steps). A
caller that runs many limited pieces in a row holds ``alarms()`` around them: inside it, each
``time_limit`` only arms and disarms the timer. The timer and handler in place before
(pytest-timeout's, say) are put back afterwards, with what was left of the earlier timer; an
earlier timer that falls due meanwhile has its handler called then, as it would have been.

Only the main thread gets signals: on any other thread ``time_limit`` cannot stop a call, and
only checks the time after the code inside it has returned. Nested limits: the outermost one
holds. Why this way: docs/decisions/0025-regex-time-limits.md.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from time import perf_counter
from types import FrameType
from typing import Any

_HAS_TIMER = hasattr(signal, "setitimer") and hasattr(signal, "SIGALRM")
#: Timers may fire this much before the deadline as perf_counter sees it.
_SLACK_S = 0.001


class MatchTimeout(Exception):
    """Matching ran past its time limit and was abandoned."""

    def __init__(self, seconds: float) -> None:
        super().__init__(f"matching took longer than {seconds:g} s and was stopped")
        self.seconds = seconds


class _State:
    #: ``alarms()`` holds the handler (how deep).
    held = 0
    #: A limit is armed, and when it falls due.
    armed = False
    deadline = 0.0
    seconds = 0.0
    #: The handler and timer in place before, and when that timer falls due.
    previous_handler: Any = None
    previous_due: float | None = None
    previous_fired = False


_state = _State()


def _on_alarm(signum: int, frame: FrameType | None) -> None:
    now = perf_counter()
    due = _state.previous_due
    if due is not None and now >= due - _SLACK_S and not _state.previous_fired:
        _state.previous_fired = True
        handler = _state.previous_handler
        if callable(handler):
            handler(signum, frame)
    if _state.armed:
        if now >= _state.deadline - _SLACK_S:
            _state.armed = False
            raise MatchTimeout(_state.seconds)
        signal.setitimer(signal.ITIMER_REAL, _state.deadline - now)  # early (an earlier timer): wait on


def can_abandon() -> bool:
    """Whether a ``time_limit`` here can stop a call that never returns by itself."""
    return _HAS_TIMER and threading.current_thread() is threading.main_thread()


@contextmanager
def alarms() -> Iterator[None]:
    """Hold the timer signal for the ``time_limit``s inside (cheaper when there are many)."""
    if not can_abandon():
        yield
        return
    if _state.held:
        _state.held += 1
        try:
            yield
        finally:
            _state.held -= 1
        return
    began = perf_counter()
    _state.previous_fired = False
    _state.previous_handler = signal.getsignal(signal.SIGALRM)
    signal.signal(signal.SIGALRM, _on_alarm)
    previous_delay, _ = signal.getitimer(signal.ITIMER_REAL)
    _state.previous_due = began + previous_delay if previous_delay > 0 else None
    _state.held = 1
    try:
        yield
    finally:
        _state.held = 0
        _state.armed = False
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, _state.previous_handler)
        signal.setitimer(signal.ITIMER_REAL, _earlier_timer_left())
        _state.previous_handler = None
        _state.previous_due = None


@contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Run the body for at most ``seconds``; past that it is abandoned with ``MatchTimeout``."""
    if _state.armed:
        yield  # the outer limit holds
        return
    if not can_abandon():
        began = perf_counter()
        yield
        if perf_counter() - began > seconds:
            raise MatchTimeout(seconds)
        return
    with alarms():
        now = perf_counter()
        _state.seconds = seconds
        _state.deadline = now + seconds
        due = _state.previous_due
        # An earlier timer falling due first rings first; the handler then waits on for ours.
        first = min(seconds, due - now) if due is not None and not _state.previous_fired else seconds
        _state.armed = True
        signal.setitimer(signal.ITIMER_REAL, max(first, 1e-6))
        try:
            yield
        finally:
            _state.armed = False
            signal.setitimer(signal.ITIMER_REAL, _earlier_timer_left())


def _earlier_timer_left() -> float:
    """What is left of the earlier timer while ``alarms()`` holds the signal (0: none)."""
    due = _state.previous_due
    if due is None or _state.previous_fired:
        return 0
    return max(due - perf_counter(), 1e-6)
