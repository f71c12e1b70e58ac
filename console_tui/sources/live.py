"""The live log stream, chosen and started in one place for every user of it: the app,
``console-tui tail`` and ``console-tui rosout``.

``open_live(queue, topic=...)`` starts what the live stream runs on (for ROS 2 an rclpy
context of the process's own) and returns a ``LiveIntake`` whose ``source`` has the
sources' shape: ``start()``, ``stop()``, ``status`` (a ``SourceStatus``), feeding
``queue``. ``close()`` stops the source and shuts its ROS down.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..model.intake_queue import IntakeQueue
from .ros2.rclpy_loader import RosUnavailable

__all__ = ["LiveIntake", "RosUnavailable", "open_live", "start_ros2"]


@dataclass
class LiveIntake:
    """A live source and what it runs on."""

    source: Any
    #: The ROS 2 runtime (``RosRuntime``) when the stream is ROS 2's, for other parts of
    #: the app that need ROS (logger levels); None otherwise.
    runtime: Any = None
    _cleanups: list[Callable[[], None]] = field(default_factory=list)

    def close(self) -> None:
        """Stop the source and shut down what it runs on; safe to call more than once."""
        try:
            self.source.stop()
        except Exception:
            pass
        cleanups, self._cleanups = self._cleanups, []
        for cleanup in reversed(cleanups):
            try:
                cleanup()
            except Exception:
                pass


def start_ros2() -> Any:
    """An rclpy context of our own (``RosRuntime``); ``RosUnavailable`` with advice if ROS 2
    cannot start."""
    from .ros2.runtime import RosRuntime

    try:
        return RosRuntime()
    except RosUnavailable:
        raise
    except Exception as error:  # rclpy present but broken (wrong RMW, bad environment)
        raise RosUnavailable(f"ROS 2 could not start: {type(error).__name__}: {error}") from None


def open_live(queue: IntakeQueue, *, topic: str | None = None) -> LiveIntake:
    """The live log stream into ``queue`` (not started yet: call ``source.start()``).

    ``topic=None`` reads ``/rosout_agg`` when something publishes it, else ``/rosout``.
    Raises ``RosUnavailable`` (with what to do) when there is no ROS to read from.
    """
    runtime = start_ros2()
    from .ros2.live_source import LiveLogSource

    try:
        source = LiveLogSource(runtime, queue, topic=topic)
    except Exception:
        runtime.shutdown()
        raise
    return LiveIntake(source, runtime, [runtime.shutdown])
