"""Running the app: the pieces put together (store, live sources, logger control, demo nodes,
the app), and everything started stopped again however the run ends."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable
from typing import Any

from .commands.arguments import EXIT_NO_ROS
from .control.fleet_control import open_fleet_loggers
from .model.store.intake_queue import IntakeQueue
from .model.store.log_store import LogStore
from .ros.ros_version import ROS1, choose_ros
from .sources.live import RosUnavailable, open_fleet, open_journal, open_live
from .system.native_output import NativeOutput


def run_app(args: argparse.Namespace, *, end_process: bool = False) -> int:
    """Run the TUI as the arguments say; returns the process exit code. With ``end_process``,
    a live session ends the process when the app is done (``end_now``)."""
    sources: list = []
    cleanups: list = []
    store = _history_store(args, cleanups)
    queue = IntakeQueue()
    logger_control = None
    files = list(getattr(args, "files", None) or [])
    robots = getattr(args, "robots", None) or []
    warehouses = getattr(args, "warehouses", None) or []
    journals = getattr(args, "journals", None) or []
    launch = getattr(args, "launch", None) or []
    live = (
        args.demo
        or getattr(args, "live", False)
        or not (files or journals or warehouses)
        or bool(robots)
        or bool(launch)
    )
    # Native code (rcl, Fast DDS) prints to the terminal below Textual: caught as records.
    native = NativeOutput(queue) if live and end_process and NativeOutput.possible() else None
    if native is not None:
        native.start()
    try:
        if robots:
            logger_control = _start_fleet(args, queue, sources, cleanups)
        elif launch:
            logger_control = _start_launch(args, queue, sources, cleanups)
        elif live:
            logger_control = _start_live(args, queue, sources, cleanups)
        for query in journals:  # the journal followed, each query by an intake process
            journal = open_journal(queue, query, log_format=getattr(args, "log_format", None) or "")
            cleanups.append(journal.close)
            sources.append(journal.source)
        if warehouses:
            sources.extend(_warehouses(args, warehouses))
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
            robots=robots,
            file_robots=getattr(args, "file_robots", None) or {},
        )
        app.native_output = native
    except BaseException as error:
        _clean_up(cleanups)  # what was started already: the live intake's process, ROS
        if native is not None:
            native.stop()
        if isinstance(error, RosUnavailable):
            print(f"console-tui: {error}", file=sys.stderr)
            return EXIT_NO_ROS
        raise
    if native is not None:
        cleanups.insert(0, native.stop)  # the last cleanup: the terminal back, what was caught on stderr
    code = run_then_clean_up(app, cleanups)
    if live and end_process:
        end_now(code)
    return code


def _history_store(args: argparse.Namespace, cleanups: list) -> LogStore:
    """The store, its full chunks on disk in a private directory of this session's (removed at
    the end; with ``--keep-history`` in the ROS log directory's kept history, kept and pruned
    to its bound); in memory only, saying why, when that directory cannot be had."""
    from .model.store.history_dir import close_spill, open_kept_spill, open_session_spill

    keep = getattr(args, "history_size", 0) if getattr(args, "keep_history", False) else 0
    if keep:
        from .ros.log_dir import KEPT_HISTORY, ros_log_dir

        spill, directory, why = open_kept_spill(ros_log_dir() / KEPT_HISTORY)
    else:
        spill, directory, why = open_session_spill()
    store = LogStore(max_messages=args.max_messages, spill=spill)
    store.memory_reason = why
    if spill is not None and directory is not None:

        def close() -> None:
            if keep:
                store.keep_rest()
            close_spill(spill, directory, bound=(keep or 0) << 20)

        cleanups.insert(0, close)  # the last: after the app and its sources
    return store


def run_then_clean_up(app: Any, cleanups: list[Callable[[], object]]) -> int:
    """Run the app; however it ends (``q``, an error in the app, SIGTERM, SIGHUP: see
    ``ui.exit_signals``) its sources stop and the cleanups run, last first: the logger
    control's puts temporary levels back. Returns the exit status."""
    try:
        app.run()
    finally:
        app.main.intake.stop_sources()
        _clean_up(cleanups)
    return app.return_code or 0


def _clean_up(cleanups: list[Callable[[], object]]) -> None:
    """Each cleanup, last first; one that fails does not keep the others from running."""
    for cleanup in reversed(cleanups):
        try:
            cleanup()
        except Exception:
            pass


def end_now(code: int) -> None:
    """End the process at once: the app has stopped everything it started (the intake
    process, demo nodes, ROS), and the interpreter's own teardown (rclpy's and Fast DDS's
    static destructors) would take seconds more, while the person who pressed ``q`` waits."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    os._exit(code)


def _warehouses(args: argparse.Namespace, addresses: list) -> list:
    """A source for each log warehouse given (started with the others after the first frame),
    the command line's rules going down into its SQL from the first query on."""
    from .model.rules.ruleset import RuleSet
    from .sources.warehouse_source import WarehouseSource

    rules = (getattr(args, "rule_set", None) or RuleSet()).with_query(getattr(args, "query_entries", ()))
    return [
        WarehouseSource(
            address,
            since_ns=getattr(args, "since_ns", None),
            until_ns=getattr(args, "until_ns", None),
            rules=rules,
            max_rows=args.max_messages,
        )
        for address in addresses
    ]


def _start_fleet(args: argparse.Namespace, queue: IntakeQueue, sources: list, cleanups: list) -> Any:
    """An intake process per robot of the fleet (``--domain``, ``--master``, ``--fleet``);
    returns the logger control of every robot's nodes (``FleetLoggerControl``)."""
    for live in open_fleet(queue, args.robots, topic=args.topic):
        cleanups.append(live.close)
        sources.append(live.source)
    control = open_fleet_loggers(args.robots, cleanups)
    cleanups.append(control.close)  # before the runtimes go: puts temporary levels back
    return control


def _start_launch(args: argparse.Namespace, queue: IntakeQueue, sources: list, cleanups: list) -> Any:
    """``console-tui run -- COMMAND``: the launch started, the live source of the ROS it runs
    feeding it (``sources/launch/launch_source.py``); returns the logger control."""
    from .sources.launch.launch_source import LaunchSource, ros_of

    launch = LaunchSource(queue, args.launch, say=lambda text: print(f"console-tui: {text}", file=sys.stderr))
    args.ros = getattr(args, "ros", None) or ros_of(args.launch)
    control = _start_live(args, launch.ros_queue, sources, cleanups)
    launch.start()  # before the app is made, as the live intake: its first lines come sooner
    sources.insert(0, launch)

    def stop_launch() -> None:
        if launch.status.running:
            print(f"console-tui: stopping the launch ({launch.name}: SIGINT sent)…", file=sys.stderr, flush=True)
        launch.stop()

    cleanups.append(stop_launch)  # the first cleanup: the launch's nodes go before ROS does
    return control


def _start_live(args: argparse.Namespace, queue: IntakeQueue, sources: list, cleanups: list) -> Any:
    """The live source for ROS 1 or ROS 2 (as ``--ros1``/``--ros2`` or the environment say),
    the demo nodes when asked; returns the logger control (or None)."""
    ros = getattr(args, "ros", None)
    if args.demo:
        ros = choose_ros(ros).version  # decided before the ROS 1 demo points us at its own master
        if ros == ROS1:
            from .demo.ros1_launcher import Ros1Demo, Ros1DemoUnavailable

            try:
                sources.append(Ros1Demo())  # first: its roscore starts before the source looks for it
            except Ros1DemoUnavailable as error:
                raise RosUnavailable(str(error)) from None
        else:
            from .demo.domain import NoFreeDomain, free_domain
            from .demo.launcher import DEMO_ENVIRONMENT

            domain = getattr(args, "demo_domain", None)
            try:
                domain = free_domain() if domain is None else domain
            except NoFreeDomain as error:
                raise RosUnavailable(str(error)) from None
            # Out of the user's graph: the demo nodes, the intake and the levels all on it.
            os.environ.update(DEMO_ENVIRONMENT, ROS_DOMAIN_ID=str(domain))
    live = open_live(queue, topic=args.topic, ros=ros)
    cleanups.append(live.close)
    sources.append(live.source)
    if not (args.demo and ros == ROS1):  # (the ROS 1 demo's roscore starts after the first frame)
        # Started now, before the app's UI is imported: the intake process's own start-up
        # (Python, rclpy, discovery) runs beside the app's instead of after its first frame,
        # and the first live row shows about a third of a second sooner (docs/performance.md,
        # "Start-up"). The app's ``start_sources`` does not start it again.
        live.source.start()
        cleanups.append(live.source.stop)
    if live.runtime is None:  # ROS 1
        from .control.ros1.logger_control import Ros1LoggerControl

        ros1_control = Ros1LoggerControl()  # the app starts it after its first frame
        cleanups.append(ros1_control.close)  # puts temporary levels back
        return ros1_control
    from .control.ros2.logger_control import Ros2LoggerControl

    logger_control = Ros2LoggerControl(live.runtime)  # the app starts it after its first frame
    cleanups.append(logger_control.close)  # before the runtime goes: puts temporary levels back
    if args.demo:
        from .demo.launcher import DemoNodes

        # the app starts it after its first frame, and stops it
        sources.append(DemoNodes(domain=int(os.environ["ROS_DOMAIN_ID"])))
    return logger_control
