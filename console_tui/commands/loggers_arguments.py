"""The command line of ``console-tui loggers``: its parser, exit statuses, and levels and
logger names as typed and printed."""

from __future__ import annotations

import argparse
import textwrap

from ..control.graph import GRAPH_MIN_S, GRAPH_QUIET_S
from ..model.levels import Severity, parse_severity
from ..model.loggers.logger_levels import DEFAULT_LOGGER
from .arguments import add_fleet_arguments, add_ros_version_arguments, add_subcommand, command_parser

EXIT_OK = 0
EXIT_ERROR = 1
EXIT_USAGE = 2
EXIT_NOT_FOUND = 3
EXIT_FAILED = 4
EXIT_INTERRUPTED = 130

EXIT_CODES = f"""exit status:
  {EXIT_OK}    done
  {EXIT_ERROR}    an unexpected error
  {EXIT_USAGE}    bad command line: unknown level name, a node name that matches several nodes;
       or ROS is not available: ROS 2 (rclpy) cannot be imported, no ROS 1 master answers
  {EXIT_NOT_FOUND}    the node is not in the ROS graph, or it has no logger services; list: no node found
  {EXIT_FAILED}    the call failed: no answer in time, node gone, level refused by the node
  {EXIT_INTERRUPTED}  interrupted (a temporary level is put back first)"""

DEFAULT_WAIT_S = 5.0
DEFAULT_LIST_WAIT_S = 10.0
DEFAULT_TIMEOUT_S = 2.0

#: How the default logger ``""`` is printed, and also accepted.
DEFAULT_LOGGER_SHOWN = '""'
_UNSET_WORDS = ("inherited", "inherit")


def build_parser() -> argparse.ArgumentParser:
    parser = command_parser(
        "loggers",
        "List ROS nodes and get or set their logger levels: in ROS 2 through the nodes' "
        "get_logger_levels and set_logger_levels services (ROS 2 Iron or later, enabled in the node), "
        "in ROS 1 through ~get_loggers and ~set_logger_level (every roscpp and rospy node). "
        "ROS 1 when ROS_VERSION=1 or a master answers at ROS_MASTER_URI, else ROS 2 (or say --ros1, --ros2).",
        EXIT_CODES,
    )
    commands = parser.add_subparsers(dest="command", required=True, metavar="{list,levels,get,set}")

    def add(
        name: str, help_text: str, wait: float, usage: str | None = None, wait_help: str = ""
    ) -> argparse.ArgumentParser:
        sub = add_subcommand(
            commands, name, help_text, epilog=EXIT_CODES, description=textwrap.fill(help_text), usage=usage
        )
        sub.add_argument(
            "--wait",
            type=seconds,
            default=wait,
            metavar="SECONDS",
            help=wait_help or f"how long to wait for the node to be discovered (default {wait:g})",
        )
        add_ros_version_arguments(sub)
        add_fleet_arguments(sub)
        if name != "list":
            sub.add_argument(
                "--robot",
                metavar="NAME",
                help="in a fleet: the robot NODE is on (or write NODE as NAME:/node)",
            )
        return sub

    listing = add(
        "list",
        "list the nodes of the ROS graph and whether they offer logger services",
        DEFAULT_LIST_WAIT_S,
        wait_help=(
            f"the longest to wait for the graph to settle: it is watched for {GRAPH_MIN_S:g} s at least, "
            f"then until no node came or went for {GRAPH_QUIET_S:g} s (default {DEFAULT_LIST_WAIT_S:g})"
        ),
    )
    listing.add_argument("--all", action="store_true", help="include hidden nodes (names starting with _)")
    listing.add_argument("--json", action="store_true", help="print JSON")

    add_subcommand(
        commands,
        "levels",
        "print the levels a logger can have: name, ROS 2 number, ROS 1 number (as 'ros2 log levels')",
        epilog=EXIT_CODES,
    )

    getting = add("get", "print loggers' levels: 'inherited' when a logger has none of its own", DEFAULT_WAIT_S)
    getting.add_argument("node", metavar="NODE", help="/ns/name, or a name that matches one node")
    getting.add_argument(
        "loggers",
        nargs="*",
        metavar="LOGGER",
        help=(
            f"logger names (default: the node's own logger and the process default {DEFAULT_LOGGER_SHOWN}; "
            "ROS 1: every logger the node lists)"
        ),
    )
    getting.add_argument(
        "--timeout",
        type=seconds,
        default=DEFAULT_TIMEOUT_S,
        metavar="SECONDS",
        help=f"per call (default {DEFAULT_TIMEOUT_S:g})",
    )
    getting.add_argument("--json", action="store_true", help="print JSON")

    setting = add(
        "set",
        "set a logger's level: NODE LEVEL [LOGGER] as 'ros2 log set' takes it, or NODE [LOGGER] LEVEL; "
        "LOGGER defaults to the node's own logger (ROS 1: rosout for rospy nodes, ros for roscpp ones); "
        "--all LEVEL sets every node's own logger",
        DEFAULT_WAIT_S,
        usage=(
            "%(prog)s [-h] [--wait SECONDS] [--timeout SECONDS] [--for SECONDS]\n"
            "       (NODE LEVEL [LOGGER] | NODE [LOGGER] LEVEL | --all LEVEL)"
        ),
    )
    setting.add_argument(
        "words",
        nargs="+",
        metavar="NODE LEVEL [LOGGER]",
        help=(
            "NODE: /ns/name, or a name that matches one node; LEVEL: debug, info, warn, error, fatal "
            "(any case), or unset to inherit again (ROS 2 only)"
        ),
    )
    setting.add_argument(
        "--all",
        dest="every_node",
        action="store_true",
        help="every node with logger services, its own logger: give only LEVEL",
    )
    setting.add_argument(
        "--timeout",
        type=seconds,
        default=DEFAULT_TIMEOUT_S,
        metavar="SECONDS",
        help=f"per call (default {DEFAULT_TIMEOUT_S:g})",
    )
    setting.add_argument(
        "--for",
        dest="duration",
        type=seconds,
        metavar="SECONDS",
        help="put the previous level back after SECONDS (the command waits until then; Ctrl+C ends it early)",
    )
    return parser


#: The longest wait, timeout or temporary level: about 11 days (``inf`` and the like overflow
#: the system's timers, and a waiter that never gives up is no timeout).
MAX_SECONDS = 1_000_000


def seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number of seconds: {text!r}") from None
    if not value >= 0:
        raise argparse.ArgumentTypeError(f"must be 0 or more: {text!r}")
    if not value <= MAX_SECONDS:  # inf too
        raise argparse.ArgumentTypeError(f"must be at most {MAX_SECONDS:,} seconds: {text!r}")
    return value


def parse_level(text: str) -> int:
    """A level name (any case) or ``unset``/``inherited``, as the ROS 2 number; ValueError if unknown."""
    if text.strip().lower() in _UNSET_WORDS:
        return int(Severity.UNSET)
    return int(parse_severity(text, allow_unset=True))


def logger_argument(text: str) -> str:
    return DEFAULT_LOGGER if text == DEFAULT_LOGGER_SHOWN else text


def shown_logger(name: str) -> str:
    return DEFAULT_LOGGER_SHOWN if name == DEFAULT_LOGGER else name
