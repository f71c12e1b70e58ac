"""``console-tui loggers``: list nodes, get and set logger levels, without the terminal UI.

Results go to stdout, one tab-separated line each (or JSON with ``--json``); messages go to
stderr. The exit status says what happened (see ``EXIT_CODES`` in ``loggers_arguments.py``, with the parser).
"""

from __future__ import annotations

import argparse
import json
import signal
import sys
import threading
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from ..model.inert_text import plural
from ..model.levels import SEVERITY_TABLE, Severity, severity_name
from ..model.loggers.logger_levels import DEFAULT_LOGGER, GraphNode, NodeLoggers, TemporaryLevel, level_text
from .arguments import EXIT_NO_ROS
from .closed_pipe import quiet_on_closed_pipe
from .loggers_arguments import (
    DEFAULT_TIMEOUT_S,
    EXIT_FAILED,
    EXIT_INTERRUPTED,
    EXIT_NOT_FOUND,
    EXIT_OK,
    EXIT_USAGE,
    build_parser,
    logger_argument,
    parse_level,
    shown_logger,
)


class CommandError(Exception):
    """A failure to report on stderr with an exit status."""

    def __init__(self, message: str, status: int) -> None:
        super().__init__(message)
        self.status = status


@quiet_on_closed_pipe
def main(argv: Sequence[str], runtime: Any = None) -> int:
    """Run ``console-tui loggers ARGV``; returns the exit status.

    ``runtime`` (a ``RosRuntime``) is one to reuse, already discovering the graph; by
    default one is made and shut down again.
    """
    args = build_parser().parse_args(list(argv))
    if args.command == "levels":
        return _levels()
    try:
        if args.command == "set":
            args.node, logger, level = _set_request(args.words, args.every_node, args.duration)
        with _interruptible(), _ros_control(args, runtime) as control:
            if args.command == "list":
                return _list(control, args)
            if args.command == "set" and args.every_node:
                return _set_all(control, level, args.wait)
            query = f"{args.robot}:{args.node}" if getattr(args, "robot", None) else args.node
            node = _find_node(control, query, args.wait)
            if args.command == "get":
                return _get(control, node, args)
            return _set(control, node, logger, level, args.duration)
    except CommandError as error:
        _say(str(error))
        return error.status
    except KeyboardInterrupt:
        _say("interrupted")
        return EXIT_INTERRUPTED


def _levels() -> int:
    """``levels``: the levels a logger can have, as ``ros2 log levels`` lists them."""
    for row in SEVERITY_TABLE:
        print(f"{row.name}\t{int(row.severity)}\t{row.ros1}")
    print(f"UNSET\t{int(Severity.UNSET)}\t-")
    return EXIT_OK


def _set_request(words: list[str], every_node: bool, duration: float | None) -> tuple[str, str | None, int]:
    """``set``'s words as (node, logger or None for the node's own, level): ``NODE LEVEL
    [LOGGER]`` (``ros2 log set``), ``NODE [LOGGER] LEVEL`` (a level last wins when both
    words are levels), or with ``--all`` only ``LEVEL``."""
    usage = "use: set NODE LEVEL [LOGGER], set NODE [LOGGER] LEVEL, or set --all LEVEL"
    if every_node:
        if len(words) != 1:
            raise CommandError(f"--all takes only a LEVEL, not {' '.join(words)}; {usage}", EXIT_USAGE)
        if duration is not None:
            raise CommandError("--for sets one node's level for a while: not with --all", EXIT_USAGE)
        node, rest = "", words
    elif len(words) in (2, 3):
        node, rest = words[0], words[1:]
    else:
        raise CommandError(
            f"{'too many' if words[3:] else 'too few'} arguments: {' '.join(words)}; {usage}", EXIT_USAGE
        )
    logger: str | None = None
    try:
        level = parse_level(rest[-1])
        if len(rest) == 2:
            logger = logger_argument(rest[0])
    except ValueError as error:
        try:
            level = parse_level(rest[0])  # ros2 log set NODE LEVEL LOGGER
        except ValueError:
            raise CommandError(str(error), EXIT_USAGE) from None
        logger = logger_argument(rest[1])
    if logger == DEFAULT_LOGGER and level == Severity.UNSET:
        raise CommandError("the process default logger cannot be unset: give it a level", EXIT_USAGE)
    return node, logger, level


@contextmanager
def _ros_control(args: argparse.Namespace, runtime: Any) -> Iterator[Any]:
    from ..ros.ros_version import ROS1, choose_ros

    if getattr(args, "robots", None):
        with _fleet_control(args) as fleet:
            yield fleet
        return
    if runtime is None and choose_ros(getattr(args, "ros", None)).version == ROS1:
        from ..control.ros1.logger_control import Ros1LoggerControl

        control = Ros1LoggerControl(
            call_timeout=getattr(args, "timeout", DEFAULT_TIMEOUT_S), include_hidden=getattr(args, "all", False)
        )
        control.start()
        try:
            yield control
        finally:
            control.close()
        return
    with _ros2_control(args, runtime) as ros2:
        yield ros2


@contextmanager
def _fleet_control(args: argparse.Namespace) -> Iterator[Any]:
    """Every robot's nodes (``--domain``, ``--master``, ``--fleet``), named ``ROBOT:/node``."""
    from ..control.fleet_control import open_fleet_loggers
    from ..ros.fleet import FleetError, check_fleet
    from ..ros.ros2.rclpy_loader import RosUnavailable

    try:
        check_fleet(args.robots)
    except FleetError as error:
        raise CommandError(str(error), EXIT_USAGE) from None
    if getattr(args, "robot", None) and args.robot not in {robot.name for robot in args.robots}:
        raise CommandError(f"--robot {args.robot}: no such robot in the fleet", EXIT_USAGE)
    cleanups: list[Any] = []
    options = {
        "call_timeout": getattr(args, "timeout", DEFAULT_TIMEOUT_S),
        "include_hidden": getattr(args, "all", False),
    }
    try:
        control = open_fleet_loggers(args.robots, cleanups, **options)
    except RosUnavailable as error:
        for cleanup in reversed(cleanups):
            cleanup()
        raise CommandError(str(error), EXIT_NO_ROS) from None
    control.start()
    try:
        yield control
    finally:
        control.close()
        for cleanup in reversed(cleanups):
            cleanup()


@contextmanager
def _ros2_control(args: argparse.Namespace, runtime: Any) -> Iterator[Any]:
    from ..control.ros2.logger_control import Ros2LoggerControl
    from ..ros.ros2.rclpy_loader import RosUnavailable
    from ..ros.ros2.runtime import RosRuntime

    own_runtime = runtime is None
    if own_runtime:
        try:
            runtime = RosRuntime()
        except RosUnavailable as error:
            raise CommandError(str(error), EXIT_NO_ROS) from None
    control = Ros2LoggerControl(
        runtime, call_timeout=getattr(args, "timeout", DEFAULT_TIMEOUT_S), include_hidden=getattr(args, "all", False)
    )
    control.start()
    try:
        yield control
    finally:
        control.close()
        if own_runtime:
            runtime.shutdown()


@contextmanager
def _interruptible() -> Iterator[None]:
    """SIGTERM ends the command like Ctrl+C does, so that temporary levels are put back."""

    def on_term(_signum: int, _frame: Any) -> None:
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGTERM, on_term)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _find_node(control: Any, query: str, wait: float) -> GraphNode:
    matches: list[GraphNode] = control.find_node(query, wait)
    if not matches and control.problem:
        raise CommandError(control.problem, EXIT_NO_ROS)
    if not matches:
        raise CommandError(
            f"no node {query!r} in the ROS graph (waited {wait:g} s); 'console-tui loggers list' shows the nodes",
            EXIT_NOT_FOUND,
        )
    if len(matches) > 1:
        names = ", ".join(node.fqn for node in matches)
        raise CommandError(f"{query!r} names several nodes: {names}; give the full name", EXIT_USAGE)
    node = matches[0]
    if not node.has_logger_services:
        raise CommandError(str(control.no_services(node.fqn)), EXIT_NOT_FOUND)
    return node


def _list(control: Any, args: argparse.Namespace) -> int:
    seen = control.wait_for_graph(args.wait)
    nodes = seen.nodes
    # ROS 1 nodes have no logger named after them: their loggers are listed by get.
    logger_of = (lambda _node: None) if control.lists_loggers else (lambda node: node.logger_name)
    if args.json:
        items = [
            {
                "node": n.fqn,
                "namespace": n.namespace,
                "name": n.name,
                "logger": logger_of(n),
                "logger_services": n.has_logger_services,
            }
            for n in nodes
        ]
        print(json.dumps(items, indent=2))
    else:
        for n in nodes:
            services = "logger-services" if n.has_logger_services else "no-logger-services"
            print(f"{n.fqn}\t{logger_of(n) or '-'}\t{services}")
    waited = f"{seen.waited_s:.1f} s"
    if not nodes and control.problem:
        raise CommandError(control.problem, EXIT_NO_ROS)
    if not nodes and control.lists_loggers:
        _say("no nodes are registered with the master")
        return EXIT_NOT_FOUND
    if not nodes:
        _say(
            f"no nodes found in {waited} (same ROS_DOMAIN_ID, RMW and discovery settings as the nodes? "
            "--wait SECONDS waits longer)"
        )
        return EXIT_NOT_FOUND
    if control.lists_loggers:
        _say(f"{plural(len(nodes), 'node')} registered with the master")
    elif seen.settled:
        _say(
            f"{plural(len(nodes), 'node')} after {waited}, the graph unchanged for the last {control.graph_quiet_s:g} s"
        )
    else:
        _say(
            f"{plural(len(nodes), 'node')} after {waited}: the graph had not settled yet (--wait SECONDS waits longer)"
        )
    return EXIT_OK


def _get(control: Any, node: GraphNode, args: argparse.Namespace) -> int:
    loggers = NodeLoggers(node, listing=control.lists_loggers)
    wanted = [logger_argument(name) for name in args.loggers]
    if not wanted and not loggers.listing:
        wanted = [node.logger_name, DEFAULT_LOGGER]
    for name in wanted:
        loggers.add_typed(name)
    loggers.update_levels(_result(control.get_levels(node.fqn, loggers.names_to_read())))
    rows = {row.name: row for row in loggers.rows()}
    chosen = [rows[name.strip()] for name in dict.fromkeys(wanted)] if wanted else list(rows.values())
    if args.json:
        items = [
            {"name": r.name, "level": r.level, "level_name": level_text(r.level), "effective": r.effective}
            for r in chosen
        ]
        print(json.dumps({"node": node.fqn, "loggers": items}, indent=2))
    else:
        for row in chosen:
            effective = severity_name(row.effective) if row.effective else "?"
            print(f"{shown_logger(row.name)}\t{level_text(row.level)}\t{effective}")
    return EXIT_OK


def _own_logger(control: Any, node: GraphNode) -> str:
    """The logger a node's own messages go through: ROS 2, its node logger; ROS 1, ``rosout``
    (rospy) or ``ros`` (roscpp), asked of the node."""
    if not control.lists_loggers:
        return node.logger_name
    try:
        return str(control.own_logger(node.fqn))
    except Exception as error:  # LoggerCallError: the text says why
        raise CommandError(str(error), EXIT_FAILED) from None


def _check_level(control: Any, level: int) -> None:
    if control.lists_loggers and level == Severity.UNSET:
        raise CommandError("ROS 1 loggers cannot be unset: give a level", EXIT_USAGE)


def _set_all(control: Any, level: int, wait: float) -> int:
    """``set --all LEVEL``: every node with logger services, its own logger; one line per node
    (``NODE LOGGER LEVEL``); a node that fails is said on stderr, and the status is then 4."""
    _check_level(control, level)
    seen = control.wait_for_graph(wait)
    nodes = [node for node in seen.nodes if node.has_logger_services]
    if not nodes and control.problem:
        raise CommandError(control.problem, EXIT_NO_ROS)
    if not nodes:
        raise CommandError(f"no node with logger services found (waited {wait:g} s)", EXIT_NOT_FOUND)
    status = EXIT_OK
    for node in nodes:
        try:
            logger = _own_logger(control, node)
            _result(control.set_level(node.fqn, logger, level))
        except CommandError as error:
            _say(str(error))
            status = EXIT_FAILED
            continue
        print(f"{node.fqn}\t{shown_logger(logger)}\t{level_text(level)}", flush=True)
    return status


def _set(control: Any, node: GraphNode, logger: str | None, level: int, duration: float | None) -> int:
    _check_level(control, level)
    logger = _own_logger(control, node) if logger is None else logger
    if duration is None:
        _result(control.set_level(node.fqn, logger, level))
        print(f"{shown_logger(logger)}\t{level_text(level)}", flush=True)
        return EXIT_OK
    ended = threading.Event()
    outcome: dict[str, Any] = {}

    def on_event(event: Any) -> None:
        entry = getattr(event, "entry", None)
        if entry is not None and (entry.node, entry.logger) == (node.fqn, logger):
            outcome["error"] = event.error
            ended.set()

    control.subscribe(on_event)
    entry: TemporaryLevel = _result(control.set_temporary(node.fqn, logger, level, duration))
    print(f"{shown_logger(logger)}\t{level_text(level)}", flush=True)
    _say(
        f"{shown_logger(logger)} on {node.fqn} at {level_text(level)} for {duration:g} s, then back to {level_text(entry.previous)}"
    )
    try:
        while not ended.wait(0.2):
            pass
    except KeyboardInterrupt:
        _result(control.end_temporary(node.fqn, logger))
        print(f"{shown_logger(logger)}\t{level_text(entry.previous)}", flush=True)
        _say("interrupted: previous level put back")
        return EXIT_INTERRUPTED
    if outcome.get("error") is not None:
        raise CommandError(f"could not put the previous level back: {outcome['error']}", EXIT_FAILED)
    print(f"{shown_logger(logger)}\t{level_text(entry.previous)}", flush=True)
    return EXIT_OK


def _result(future: Any) -> Any:
    """Wait for a control call; its failure becomes a ``CommandError`` with the matching status."""
    from ..control.errors import LoggerCallError, NodeNotFound, NoLoggerServices

    try:
        return future.result()
    except (NodeNotFound, NoLoggerServices) as error:
        raise CommandError(str(error), EXIT_NOT_FOUND) from None
    except LoggerCallError as error:
        raise CommandError(str(error), EXIT_FAILED) from None


def _say(message: str) -> None:
    print(f"console-tui loggers: {message}", file=sys.stderr, flush=True)
