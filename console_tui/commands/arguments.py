"""Command-line arguments that several ``console-tui`` commands share."""

from __future__ import annotations

import argparse
import textwrap
from collections.abc import Callable, Sequence

from ..ros.ros_version import ROS1, ROS2

#: "ROS is not available" (no rclpy in this Python, no ROS 1 master answers, no roscore for
#: the ROS 1 demo): one exit status for the app and every subcommand, argparse's for a bad
#: command line (the command cannot do its job as asked, and says what to do on stderr).
EXIT_NO_ROS = 2
#: Where the documentation lives (``--help`` texts point here, not to the README).
DOCS_URL = "https://console-tui.github.io/console-tui/"


def add_log_format_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--log-format",
        metavar="FMT",
        help=(
            "the RCUTILS_CONSOLE_OUTPUT_FORMAT that ROS 2 log files were written with, for example "
            "'[{severity}] [{time}] [{name}]: {message}' (the default, always recognised; "
            "$RCUTILS_CONSOLE_OUTPUT_FORMAT is tried too)"
        ),
    )


def add_last_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--last",
        "--latest",
        action="store_true",
        help=(
            "the newest run in the ROS log directory ($ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log): "
            "the folder 'latest' points to, every log in it merged"
        ),
    )


def whole_number(text: str, what: str = "a whole number") -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not {what}: {text!r}") from None


def positive_int(text: str) -> int:
    if whole_number(text) < 1:
        raise argparse.ArgumentTypeError("must be at least 1")
    return int(text)


def domain_id(text: str) -> int:
    """A ROS 2 domain id, 0 to 232 (the ports of higher ones do not fit)."""
    what = "a domain id (0 to 232)"
    if not 0 <= whole_number(text, what) <= 232:
        raise argparse.ArgumentTypeError(f"not {what}: {text!r}")
    return int(text)


_SIZE_UNITS = {"": 1, "b": 1, "k": 1 << 10, "m": 1 << 20, "g": 1 << 30, "t": 1 << 40}


def parse_size(text: str) -> int:
    """A size in bytes from ``500``, ``10K``, ``100M``, ``1.5G`` (powers of 1024; ``KiB``/``KB`` alike)."""
    cleaned = text.strip().lower().replace(" ", "")
    for suffix in ("ib", "b"):
        if cleaned.endswith(suffix) and cleaned[: -len(suffix)][-1:] in ("k", "m", "g", "t"):
            cleaned = cleaned[: -len(suffix)]
    number, unit = cleaned.rstrip("kmgtb"), cleaned[len(cleaned.rstrip("kmgtb")) :]
    try:
        value = float(number)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a size: {text!r} (for example 500M, 1G, 1.5G)") from None
    if unit not in _SIZE_UNITS or value < 0:
        raise argparse.ArgumentTypeError(f"not a size: {text!r} (for example 500M, 1G, 1.5G)")
    return int(value * _SIZE_UNITS[unit])


def size_text(size: int) -> str:
    """A size as ``du -h`` prints it: ``512``, ``10K``, ``1.5M``, ``12G`` (powers of 1024)."""
    value = float(size)
    for unit in ("", "K", "M", "G", "T"):
        if value < 1024 or unit == "T":
            if not unit:
                return f"{int(value)}"
            return f"{value:.1f}{unit}" if value < 10 else f"{value:.0f}{unit}"
        value /= 1024
    raise AssertionError("unreachable")


def check_rule_arguments(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Compile ``--query`` and read ``--rules`` before anything starts; a problem exits 2.

    Sets ``args.query_entries`` (the query's rule entries, or ``()``) and ``args.rule_set``
    (the file's ``RuleSet``, or None).
    """
    from ..model.inert_text import one_line
    from ..model.rules.query import QueryError, caret_line, parse_query
    from ..model.rules.rule import RuleError
    from ..model.rules.rulesfile import last_rules_path, load_rules

    args.query_entries = ()
    args.rule_set = None
    if args.query:
        try:
            args.query_entries = parse_query(args.query, utc=args.utc)
        except QueryError as error:
            parser.error(
                f"--query is not valid (at {(error.position or 0) + 1}):\n{caret_line(one_line(args.query), error)}"
            )
    if args.rules:
        path = args.rules
        if path == "last":
            path = last_rules_path()
            if not path.exists():
                parser.error(f"--rules last: no rule set was saved by an earlier run ({path})")
        try:
            args.rule_set = load_rules(path)
        except RuleError as error:
            parser.error(f"--rules: {one_line(error.message)}")


def add_ros_version_arguments(parser: argparse.ArgumentParser) -> None:
    """``--ros1`` / ``--ros2``; the choice lands in ``args.ros`` (None: decide from the environment)."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--ros1",
        dest="ros",
        action="store_const",
        const=ROS1,
        help="ROS 1: talk to the master at ROS_MASTER_URI (default: ROS 1 when ROS_VERSION=1 or a master answers there, else ROS 2)",
    )
    group.add_argument("--ros2", dest="ros", action="store_const", const=ROS2, help="ROS 2, through rclpy")


def command_parser(name: str, description: str, epilog: str) -> argparse.ArgumentParser:
    """The parser of ``console-tui NAME``: ``description`` filled to 70 columns, then
    ``epilog`` as written (its exit statuses)."""
    return argparse.ArgumentParser(
        prog=f"console-tui {name}",
        description=textwrap.fill(description),
        epilog=epilog,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )


def add_subcommand(
    commands: argparse._SubParsersAction,
    name: str,
    help_text: str,
    *,
    epilog: str,
    description: str | None = None,
    usage: str | None = None,
) -> argparse.ArgumentParser:
    """A sub-command (``check``, ``list``...) whose help ends with ``epilog`` as written (exit statuses)."""
    sub: argparse.ArgumentParser = commands.add_parser(
        name,
        help=help_text,
        description=help_text if description is None else description,
        epilog=epilog,
        usage=usage,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    return sub


class _AddRobots(argparse.Action):
    """Adds the robots an option names to ``args.robots``, in command-line order."""

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: object,
        option_string: str | None = None,
    ) -> None:
        robots = list(getattr(namespace, self.dest, None) or [])
        robots.extend(values if isinstance(values, list) else [values])
        setattr(namespace, self.dest, robots)


def _robots_type(read: Callable[[str], object]) -> Callable[[str], object]:
    from ..ros.fleet import FleetError

    def parse(text: str) -> object:
        try:
            return read(text)
        except FleetError as error:
            raise argparse.ArgumentTypeError(str(error)) from None

    return parse


def add_fleet_arguments(parser: argparse.ArgumentParser) -> None:
    """``--domain N[=NAME]``, ``--master URI[=NAME]``, ``--fleet FILE``, repeatable and mixed:
    the robots land in ``args.robots`` (``ros.fleet.Robot``, in order; None when none given)."""
    from ..ros.fleet import load_fleet, parse_domain, parse_master

    group = parser.add_argument_group(
        "a fleet (several robots at once; each option may be given more than once, and mixed)"
    )
    options = (
        ("--domain", "N[=NAME]", parse_domain, "read the robot on ROS 2 domain N, named NAME (default domainN)"),
        (
            "--master",
            "URI[=NAME]",
            parse_master,
            "read the robot whose ROS 1 master is at URI (http://host:port), named NAME",
        ),
        (
            "--fleet",
            "FILE",
            load_fleet,
            "read every robot of this fleet file (TOML: [[robot]] tables with name, domain or master, "
            "optional topic and colour)",
        ),
    )
    for option, metavar, read, help_text in options:
        group.add_argument(
            option, dest="robots", metavar=metavar, action=_AddRobots, type=_robots_type(read), help=help_text
        )


def add_robot_argument(parser: argparse.ArgumentParser) -> None:
    """``--robot NAME`` (read by ``robot_files`` before the parser): the files after it are
    that robot's; ``--robots-from-names``: each file or folder is a robot named for it."""
    parser.add_argument(
        "--robot",
        metavar="NAME",
        help="the FILEs given after it are this robot's (its name in the Robot column); give it again "
        "before another robot's files",
    )
    parser.add_argument(
        "--robots-from-names",
        action="store_true",
        help="each FILE or folder given is a robot's, named for it (picker/ or picker.log: picker), "
        "unless --robot names it",
    )


def robots_from_names(files: Sequence[str], robots: dict[str, str]) -> dict[str, str]:
    """``robots`` with each file that has none named for its own name (``--robots-from-names``)."""
    from ..ros.fleet import robot_name_for

    return {**{file: robot_name_for(file) for file in files}, **robots}


def robot_files(parser: argparse.ArgumentParser, argv: Sequence[str]) -> tuple[list[str], dict[str, str]]:
    """``argv`` without its ``--robot NAME`` options, and the robot of each file given after one
    (by the file's text as given). With a ``--robot``, the files come last in the ``argv``
    returned (after ``--``), so that files between options parse. A bad name exits 2."""
    from ..ros.fleet import FleetError, check_robot_name

    takes_value = {name for action in parser._actions for name in action.option_strings if action.nargs != 0}
    kept: list[str] = []
    files: list[str] = []
    robots: dict[str, str] = {}
    robot = ""
    at = 0
    only_files = False
    while at < len(argv):
        token = argv[at]
        at += 1
        if not only_files and (token == "--robot" or token.startswith("--robot=")):
            if "=" in token:
                name = token.partition("=")[2]
            elif at < len(argv):
                name, at = argv[at], at + 1
            else:
                parser.error("--robot needs a robot's name")
            try:
                robot = check_robot_name(name)
            except FleetError as error:
                parser.error(f"--robot: {error}")
            continue
        if only_files or not token.startswith("-") or token == "-":
            files.append(token)
            if robot:
                robots[token] = robot
        elif token == "--":
            only_files = True
        else:
            kept.append(token)
            if token in takes_value and at < len(argv):
                kept.append(argv[at])
                at += 1
    if not robot:  # no --robot: as given
        return list(argv), robots
    return [*kept, "--", *files], robots


def check_fleet_arguments(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Two robots with one name, domain or master exit 2 saying which."""
    from ..ros.fleet import FleetError, check_fleet

    try:
        check_fleet(getattr(args, "robots", None) or [])
    except FleetError as error:
        parser.error(str(error))
