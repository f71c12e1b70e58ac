"""The live log stream, chosen and started in one place for every user of it: the app
and ``console-tui tail`` (``console-tui rosout`` is ROS 2's and uses ``start_ros2``).

``open_live(queue, topic=..., ros=...)`` picks ROS 1 or ROS 2 (``--ros1``/``--ros2``, else
the environment: ``sources.ros_version``), starts what the stream runs on (for ROS 2 an
rclpy context of the process's own) and returns a ``LiveIntake`` whose ``source`` has the
sources' shape: ``start()``, ``stop()``, ``status`` (a ``SourceStatus``), feeding
``queue``. ``close()`` stops the source and shuts its ROS down.

``open_fleet(queue, robots, topic=...)`` does the same for each robot of a fleet
(``sources.fleet``: several ROS 2 domains and ROS 1 masters at once): an intake process per
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

from ..model.intake_queue import IntakeQueue
from .fleet import Robot
from .ros2.rclpy_loader import RosUnavailable
from .ros_version import ROS1, ROS2, choose_ros

HOW_TO_USE_ROS1 = (
    "  - For ROS 1: set ROS_MASTER_URI to the master (and ROS_IP to this machine's address) and run\n"
    "      console-tui --ros1"
)

__all__ = [
    "LiveIntake",
    "RosUnavailable",
    "open_fleet",
    "open_fleet_loggers",
    "open_live",
    "open_stream",
    "start_ros2",
]


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


def start_ros2(domain_id: int | None = None, *, deferred: bool = False) -> Any:
    """An rclpy context of our own (``RosRuntime``), on ``domain_id`` (default ``ROS_DOMAIN_ID``'s);
    ``RosUnavailable`` with advice if ROS 2 cannot start. ``deferred``: rclpy is imported at the
    context's first use (see ``RosRuntime``)."""
    from .ros2.runtime import RosRuntime

    try:
        return RosRuntime(domain_id=domain_id, deferred=deferred)
    except RosUnavailable:
        raise
    except Exception as error:  # rclpy present but broken (wrong RMW, bad environment)
        raise RosUnavailable(f"ROS 2 could not start: {type(error).__name__}: {error}") from None


def open_live(queue: IntakeQueue, *, topic: str | None = None, ros: int | None = None) -> LiveIntake:
    """The live log stream into ``queue`` (not started yet: call ``source.start()``).

    ``ros`` is 1 or 2 (``--ros1``/``--ros2``), or None to decide from the environment.
    ``topic=None`` reads ``/rosout_agg`` when something publishes it, else ``/rosout``.
    Raises ``RosUnavailable`` (with what to do) when there is no ROS to read from.
    """
    from .intake_process.parent import ProcessSource

    choice = choose_ros(ros)
    if choice.version == ROS1:
        from .ros1.environment import Ros1Environment

        origin = f"ROS 1 {Ros1Environment.from_environ().master_uri}"
        return LiveIntake(ProcessSource(queue, "ros1", topic=topic, origin=origin))
    try:
        runtime = start_ros2(deferred=True)  # this process's ROS: for the logger levels, later
    except RosUnavailable as error:
        raise RosUnavailable(f"{error}\n{HOW_TO_USE_ROS1}") from None
    origin = f"ROS 2 domain {os.environ.get('ROS_DOMAIN_ID', '0') or '0'}"
    # A ROS 1 user would wonder why ROS 2: the status line says so.
    remark = f"no ROS 1 master answered at {choice.master_silent} (--ros1 waits for it)" if choice.master_silent else ""
    source = ProcessSource(queue, "ros2", topic=topic, origin=origin, remark=remark)
    return LiveIntake(source, runtime, [runtime.shutdown])


def open_fleet(queue: IntakeQueue, robots: Sequence[Robot], *, topic: str | None = None) -> list[LiveIntake]:
    """An intake process per robot into ``queue`` (none started yet), each robot's records and
    status named for it; a robot's own topic before ``topic``. One robot's trouble (a silent
    domain, a master gone, its process ended) stays in its own source's status."""
    from .intake_process.parent import ProcessSource

    return [
        LiveIntake(
            ProcessSource(
                queue,
                "ros2" if robot.ros == ROS2 else "ros1",
                topic=robot.topic or topic,
                env=robot.environment(),
                origin=robot.origin,
                robot=robot.name,
            )
        )
        for robot in robots
    ]


def open_stream(
    queue: IntakeQueue, robots: Sequence[Robot] | None, *, topic: str | None = None, ros: int | None = None
) -> list[LiveIntake]:
    """The log stream the headless commands read (``tail``, ``ship``): each robot of a fleet
    when ``robots`` are given (``--domain``, ``--master``, ``--fleet``), else the one source of
    the environment (``--ros1``/``--ros2``); none started yet. ``RosUnavailable`` as ``open_live``."""
    if robots:
        return open_fleet(queue, robots, topic=topic)
    return [open_live(queue, topic=topic, ros=ros)]


def open_fleet_loggers(robots: Sequence[Robot], cleanups: list[Callable[[], object]], **options: Any) -> Any:
    """The logger control of every robot's nodes (``FleetLoggerControl``, not started): for a
    ROS 2 robot an rclpy context of this process on its domain, for a ROS 1 robot its master;
    ``options`` go to each robot's control (``call_timeout``, ``include_hidden``). What to shut
    down after the control is closed goes into ``cleanups``. ``RosUnavailable`` when a ROS 2
    robot's context cannot start."""
    from .loggers.control import LoggerControl
    from .loggers.fleet_control import FleetLoggerControl

    controls: dict[str, LoggerControl] = {}
    for robot in robots:
        if robot.ros == ROS2:
            from .ros2.logger_control import Ros2LoggerControl

            runtime = start_ros2(robot.domain)
            cleanups.append(runtime.shutdown)
            controls[robot.name] = Ros2LoggerControl(runtime, **options)
        else:
            from .ros1.environment import Ros1Environment
            from .ros1.logger_control import Ros1LoggerControl

            controls[robot.name] = Ros1LoggerControl(Ros1Environment.from_environ(robot.environment()), **options)
    return FleetLoggerControl(controls)
