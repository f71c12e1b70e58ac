"""Abandoning text matching that runs too long.

A regular expression such as ``(a+)+$`` backtracks catastrophically: one ``re.search`` over
thirty ``a`` and a ``b`` takes minutes, in one C call that nothing on the same thread can
interrupt by returning. But Python's regex engine checks for pending signals every 4096
steps of a match, and a Python signal handler that raises ends the match with its
exception. ``time_limit(seconds)`` arms a one-shot real-time timer (``SIGALRM``) around the
code inside it: past ``seconds`` that code is abandoned with ``MatchTimeout``, wherever it
is, a catastrophic ``re.search`` included. Python's ``re`` keeps its semantics and its
speed; nothing needs installing.

The timer and handler in place before (pytest-timeout's, say) are put back afterwards, with
what was left of the earlier timer; an earlier timer that falls due inside the limit has its
handler called then, as it would have been.

Only the main thread gets signals: on any other thread ``time_limit`` cannot stop a call,
and only checks the time after the code inside it has returned. Nested limits: the
outermost one holds.
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


class _Limit:
    """The limit in force (at most one: nested limits leave the outermost in charge)."""

    armed = False
    deadline = 0.0
    seconds = 0.0
    #: The handler and timer that were in place before, and when that timer falls due.
    previous_handler: Any = None
    previous_due: float | None = None
    previous_fired = False


_limit = _Limit()


def _on_alarm(signum: int, frame: FrameType | None) -> None:
    now = perf_counter()
    due = _limit.previous_due
    if due is not None and now >= due - _SLACK_S and not _limit.previous_fired:
        _limit.previous_fired = True
        handler = _limit.previous_handler
        if callable(handler):
            handler(signum, frame)
    if _limit.armed:
        if now >= _limit.deadline - _SLACK_S:
            _limit.armed = False
            raise MatchTimeout(_limit.seconds)
        signal.setitimer(signal.ITIMER_REAL, _limit.deadline - now)  # early (an earlier timer): wait on


def can_abandon() -> bool:
    """Whether a ``time_limit`` here can stop a call that never returns by itself."""
    return _HAS_TIMER and threading.current_thread() is threading.main_thread()


@contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Run the body for at most ``seconds``; past that it is abandoned with ``MatchTimeout``."""
    if _limit.armed:
        yield  # the outer limit holds
        return
    if not can_abandon():
        began = perf_counter()
        yield
        if perf_counter() - began > seconds:
            raise MatchTimeout(seconds)
        return
    began = perf_counter()
    _limit.seconds = seconds
    _limit.deadline = began + seconds
    _limit.previous_fired = False
    _limit.previous_handler = signal.getsignal(signal.SIGALRM)
    signal.signal(signal.SIGALRM, _on_alarm)
    previous_delay, _ = signal.setitimer(signal.ITIMER_REAL, seconds)
    _limit.previous_due = began + previous_delay if previous_delay > 0 else None
    if previous_delay and previous_delay < seconds:
        signal.setitimer(signal.ITIMER_REAL, previous_delay)  # the earlier timer first, then ours
    _limit.armed = True
    try:
        yield
    finally:
        _limit.armed = False
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, _limit.previous_handler)
        due = _limit.previous_due
        if due is not None and not _limit.previous_fired:
            signal.setitimer(signal.ITIMER_REAL, max(due - perf_counter(), 1e-6))
        _limit.previous_handler = None
        _limit.previous_due = None
