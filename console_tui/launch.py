"""Putting the pieces together for a run: store, sources, demo nodes, the app."""

from __future__ import annotations

import argparse
import os
import sys
from dataclasses import replace
from typing import Any

from .model.intake_queue import IntakeQueue
from .model.store import LogStore
from .sources.ros2.rclpy_loader import RosUnavailable
from .sources.ros_version import ROS1, choose_ros

HOW_TO_USE_ROS1 = (
    "  - For ROS 1: set ROS_MASTER_URI to the master (and ROS_IP to this machine's address) and run\n"
    "      console-tui --ros1"
)


def run_app(args: argparse.Namespace) -> int:
    """Run the TUI as the arguments say; returns the process exit code."""
    store = LogStore(max_messages=args.max_messages)
    queue = IntakeQueue()
    sources: list = []
    cleanups: list = []
    logger_control = None
    files = list(getattr(args, "files", None) or [])
    live = args.demo or getattr(args, "live", False) or not files
    if live:
        try:
            logger_control = _start_live(args, queue, sources, cleanups)
        except RosUnavailable as error:
            print(f"console-tui: {error}", file=sys.stderr)
            return 2
    from .ui.app import ConsoleApp

    app = ConsoleApp(
        store=store,
        queue=queue,
        sources=sources,
        utc=args.utc,
        files=files,
        log_format=getattr(args, "log_format", None),
        logger_control=logger_control,
        rules=getattr(args, "rule_set", None),
        query=getattr(args, "query", None) or "",
        remember_rules=True,
    )
    try:
        app.run()
    finally:
        app.stop_sources()
        for cleanup in reversed(cleanups):
            try:
                cleanup()
            except Exception:
                pass
    return app.return_code or 0


def _start_live(args: argparse.Namespace, queue: IntakeQueue, sources: list, cleanups: list) -> Any:
    """The live source for ROS 1 or ROS 2 (as ``--ros1``/``--ros2`` or the environment say),
    the demo nodes when asked; returns the logger control (or None)."""
    choice = choose_ros(getattr(args, "ros", None))
    if choice.version == ROS1:
        return _start_ros1(args, queue, sources, cleanups)
    if args.demo:
        from .demo.launcher import DEMO_ENVIRONMENT

        os.environ.update(DEMO_ENVIRONMENT)
    try:
        runtime = _start_ros()
    except RosUnavailable as error:
        raise RosUnavailable(f"{error}\n{HOW_TO_USE_ROS1}") from None
    cleanups.append(runtime.shutdown)
    from .sources.ros2.live_source import LiveLogSource
    from .sources.ros2.logger_control import Ros2LoggerControl

    source = LiveLogSource(runtime, queue, topic=args.topic)
    source.status = replace(source.status, origin=f"ROS 2 domain {os.environ.get('ROS_DOMAIN_ID', '0') or '0'}")
    sources.append(source)
    logger_control = Ros2LoggerControl(runtime)  # the app starts it after its first frame
    cleanups.append(logger_control.close)  # before the runtime goes: puts temporary levels back
    if args.demo:
        from .demo.launcher import DemoNodes

        sources.append(DemoNodes())  # the app starts it after its first frame, and stops it
    return logger_control


def _start_ros1(args: argparse.Namespace, queue: IntakeQueue, sources: list, cleanups: list) -> Any:
    from .sources.ros1.live_source import Ros1LiveSource
    from .sources.ros1.logger_control import Ros1LoggerControl

    if args.demo:
        from .demo.ros1_launcher import Ros1Demo, Ros1DemoUnavailable

        try:
            # First: it points this process at its own roscore, and starts before the source.
            sources.append(Ros1Demo())
        except Ros1DemoUnavailable as error:
            raise RosUnavailable(str(error)) from None
    sources.append(Ros1LiveSource(queue, topic=args.topic))
    logger_control = Ros1LoggerControl()  # the app starts it after its first frame
    cleanups.append(logger_control.close)  # puts temporary levels back
    return logger_control


def _start_ros():
    from .sources.ros2.runtime import RosRuntime

    try:
        return RosRuntime()
    except RosUnavailable:
        raise
    except Exception as error:  # rclpy present but broken (wrong RMW, bad environment)
        raise RosUnavailable(f"ROS 2 could not start: {type(error).__name__}: {error}") from None
