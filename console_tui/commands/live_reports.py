"""What the live sources of a headless command (``tail``, ``ship``) say on standard error:
each source's problem when it changes, its losses at most every ``LOSS_REPORT_S``, and once
that the slower intake path is in use and that the middleware does not filter by ``--level``.
A fleet's robot is named before what it says."""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from ..sources.live import LiveIntake

#: Losses are told at most this often.
LOSS_REPORT_S = 5.0


@dataclass
class _Told:
    """What was said of a live source: its problem, its losses and when."""

    problem: str = ""
    lost: int = 0
    lost_at: float = 0.0


class LiveReports:
    """What the live sources said, told once (``tell``, called every turn of the loop)."""

    def __init__(
        self, lives: Sequence[LiveIntake], complain: Callable[[str], None], clock: Callable[[], float] = time.monotonic
    ) -> None:
        self._lives = list(lives)
        self._complain = complain
        self._clock = clock
        self._told = [_Told() for _ in self._lives]
        self._slow_told = self._filter_told = False

    def tell(self) -> None:
        """Say what changed since the last call."""
        for live, said in zip(self._lives, self._told, strict=True):
            status = live.source.status
            robot = f"{status.robot}: " if status.robot else ""  # a fleet's robot
            if status.problem and status.problem != said.problem:
                self._complain(robot + status.problem)
            said.problem = status.problem
            slow = status.slow_path_text() if status.path_note and not self._slow_told else ""
            if slow:  # (nothing while the loop in C is being built)
                self._complain(slow)
                self._slow_told = True
            if status.level_filter_note and not self._filter_told:  # the middleware does not filter
                self._complain(f"--level: {status.level_filter_text()}")
                self._filter_told = True
            now = self._clock()
            if status.lost > said.lost and now - said.lost_at >= LOSS_REPORT_S:
                self._complain(robot + status.loss_text())
                said.lost, said.lost_at = status.lost, now
