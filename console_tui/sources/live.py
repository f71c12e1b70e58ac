"""The live log stream, chosen and started in one place for every user of it: the app
and ``console-tui tail`` (``console-tui rosout`` is ROS 2's and uses ``start_ros2`` of
``ros/ros2/runtime.py``). The logger control of a fleet's nodes opens in ``control/``.

``open_live(queue, topic=..., ros=...)`` picks ROS 1 or ROS 2 (``--ros1``/``--ros2``, else
the environment: ``ros.ros_version``), starts what the stream runs on (for ROS 2 an
rclpy context of the process's own) and returns a ``LiveIntake`` whose ``source`` has the
sources' shape: ``start()``, ``stop()``, ``status`` (a ``SourceStatus``), feeding
``queue``. ``close()`` stops the source and shuts its ROS down.

``open_fleet(queue, robots, topic=...)`` does the same for each robot of a fleet
(``ros.fleet``: several ROS 2 domains and ROS 1 masters at once): an intake process per
robot, all feeding the one queue, each record named for its robot.

The stream, ROS 1's and ROS 2's alike, is taken in a child process (``intake_process``),
where nothing the app does can hold it up; for ROS 2 this process keeps an rclpy context
of its own for the logger levels, made at its first use.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..model.store.intake_queue import IntakeQueue
from ..ros.fleet import Robot
from ..ros.ros2.rclpy_loader import RosUnavailable
from ..ros.ros_version import ROS1, ROS2, choose_ros
from .journal.journalctl import JournalQuery

HOW_TO_USE_ROS1 = (
    "  - For ROS 1: set ROS_MASTER_URI to the master (and ROS_IP to this machine's address) and run\n"
    "      console-tui --ros1"
)

__all__ = ["LiveIntake", "RosUnavailable", "open_fleet", "open_journal", "open_live", "open_stream"]


@dataclass
class LiveIntake:
    """A live source and what it runs on."""

    source: Any
    #: The ROS 2 runtime (``RosRuntime``) when the stream is ROS 2's, for other parts of
    #: the app that need ROS (logger levels); None for ROS 1.
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


def open_live(
    queue: IntakeQueue, *, topic: str | None = None, ros: int | None = None, min_level: int = 0
) -> LiveIntake:
    """The live log stream into ``queue`` (not started yet: call ``source.start()``).

    ``ros`` is 1 or 2 (``--ros1``/``--ros2``), or None to decide from the environment.
    ``topic=None`` reads ``/rosout_agg`` when something publishes it, else ``/rosout``.
    ``min_level`` (a ROS 2 severity): only messages of it and worse, asked of the middleware
    where it can (``tail --level``). Raises ``RosUnavailable`` (with what to do) when there is
    no ROS to read from.
    """
    from .intake_process.parent import ProcessSource

    choice = choose_ros(ros)
    args = _level_args(min_level)
    if choice.version == ROS1:
        from ..ros.ros1.environment import Ros1Environment

        origin = f"ROS 1 {Ros1Environment.from_environ().master_uri}"
        return LiveIntake(ProcessSource(queue, "ros1", topic=topic, args=args, origin=origin))
    from ..ros.ros2.runtime import start_ros2

    try:
        runtime = start_ros2(deferred=True)  # this process's ROS: for the logger levels, later
    except RosUnavailable as error:
        raise RosUnavailable(f"{error}\n{HOW_TO_USE_ROS1}") from None
    origin = f"ROS 2 domain {os.environ.get('ROS_DOMAIN_ID', '0') or '0'}"
    # A ROS 1 user would wonder why ROS 2: the status line says so.
    remark = f"no ROS 1 master answered at {choice.master_silent} (--ros1 waits for it)" if choice.master_silent else ""
    source = ProcessSource(queue, "ros2", topic=topic, args=args, origin=origin, remark=remark)
    return LiveIntake(source, runtime, [runtime.shutdown])


def _level_args(min_level: int) -> list[str]:
    """The intake process's arguments for a lowest severity (none for 0)."""
    return ["--min-level", str(int(min_level))] if min_level else []


def open_fleet(
    queue: IntakeQueue, robots: Sequence[Robot], *, topic: str | None = None, min_level: int = 0
) -> list[LiveIntake]:
    """An intake process per robot into ``queue`` (none started yet), each robot's records and
    status named for it; a robot's own topic before ``topic``; ``min_level`` as ``open_live``
    takes it. One robot's trouble (a silent domain, a master gone, its process ended) stays in
    its own source's status."""
    from .intake_process.parent import ProcessSource

    return [
        LiveIntake(
            ProcessSource(
                queue,
                "ros2" if robot.ros == ROS2 else "ros1",
                topic=robot.topic or topic,
                args=_level_args(min_level),
                env=robot.environment(),
                origin=robot.origin,
                robot=robot.name,
            )
        )
        for robot in robots
    ]


def open_stream(
    queue: IntakeQueue,
    robots: Sequence[Robot] | None,
    *,
    topic: str | None = None,
    ros: int | None = None,
    min_level: int = 0,
) -> list[LiveIntake]:
    """The log stream the headless commands read (``tail``, ``ship``): each robot of a fleet
    when ``robots`` are given (``--domain``, ``--master``, ``--fleet``), else the one source of
    the environment (``--ros1``/``--ros2``); none started yet; ``min_level`` as ``open_live``.
    ``RosUnavailable`` as ``open_live``."""
    if robots:
        return open_fleet(queue, robots, topic=topic, min_level=min_level)
    return [open_live(queue, topic=topic, ros=ros, min_level=min_level)]


def open_journal(queue: IntakeQueue, query: JournalQuery, *, log_format: str = "") -> LiveIntake:
    """The journal ``query`` asks for, followed into ``queue`` by an intake process of its own
    (``journal/journal_source.py``; not started yet). ``log_format``: the
    ``RCUTILS_CONSOLE_OUTPUT_FORMAT`` its ROS 2 lines were written with (default: the
    environment's, else ROS 2's default)."""
    from .intake_process.parent import ProcessSource

    args = [f"--unit={unit}" for unit in query.units] + [f"--journal-file={name}" for name in query.files]
    if query.directory:
        args.append(f"--journal-directory={query.directory}")
    if query.since:
        args.append(f"--since={query.since}")
    template = log_format or os.environ.get("RCUTILS_CONSOLE_OUTPUT_FORMAT", "")
    if template:
        args.append(f"--log-format={template}")
    return LiveIntake(ProcessSource(queue, "journal", args=args, origin=query.describe()))
