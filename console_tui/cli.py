# PYTHON_ARGCOMPLETE_OK
"""The ``console-tui`` command line."""

from __future__ import annotations

import argparse
import gc
import importlib
import os
import sys
import textwrap
from collections.abc import Sequence

from . import __version__
from .commands.arguments import (
    DOCS_URL,
    EXIT_NO_ROS,
    add_fleet_arguments,
    add_last_argument,
    add_log_format_argument,
    add_robot_argument,
    add_ros_version_arguments,
    check_fleet_arguments,
    check_rule_arguments,
    domain_id,
    positive_int,
    robot_files,
    robots_from_names,
)
from .commands.location_options import add_location_arguments, apply_location_arguments
from .model.store.history_dir import KEPT_BYTES
from .model.store.log_store import DEFAULT_MAX_MESSAGES, MEMORY_BOUND

#: ``console-tui VERB ...`` runs ``console_tui.commands.VERB.main``; what each does.
SUBCOMMANDS: dict[str, str] = {
    "loggers": "lists and sets logger levels without the TUI",
    "convert": "converts log files and recordings",
    "tail": "prints the live log stream or log files, filtered, on standard output",
    "rosout": "runs the rosout node for ROS 2: /rosout_agg and rosout.log",
    "clean": "checks and purges the ROS log directory (rosclean)",
    "ship": "sends the log stream to the log warehouse (OTLP, ClickHouse, chDB), spooled on disk",
    "serve": "serves the console to web browsers, one console per tab (the [web] extra)",
}
#: Other names of subcommands: ``ros2 log``'s words for them.
ALIASES: dict[str, str] = {"watch": "tail"}


#: ``console-tui run -- COMMAND``: the app, reading a launch it starts (``launch_parser``).
RUN = "run"

EPILOG = "\n".join(
    [
        "subcommands (each has --help):",
        *(f"  {name:9} {what}" for name, what in SUBCOMMANDS.items()),
        f"  {RUN:9} runs a launch (ros2 launch, roslaunch) and shows what it prints with the live log stream",
        *(f"  {alias:9} the same as '{verb}' (as in 'ros2 log {alias}')" for alias, verb in ALIASES.items()),
        "",
        "exit status:",
        "  0  done",
        f"  {EXIT_NO_ROS}  bad command line, no terminal (the console needs one: use 'console-tui tail'), or ROS",
        "     is not available (no rclpy in this Python, no roscore for --demo --ros1); ROS not available",
        f"     is {EXIT_NO_ROS} in every subcommand too",
        "",
        "install extras: [ros] (ROS 2 Kilted from PyPI) or [jazzy] (ROS 2 Jazzy), never both; [files] for",
        "recordings (.bag, .mcap, .db3). The [ros] and [jazzy] wheels exist for x86_64 Linux only: elsewhere",
        "(aarch64 robots) source your ROS first.",
        'shell completion (bash, zsh): eval "$(register-python-argcomplete console-tui)" in ~/.bashrc',
        f"documentation: {DOCS_URL} (the query line: {DOCS_URL}rules/#the-query-line)",
    ]
)


class _Version(argparse.Action):
    """``--version``: console-tui's, then Textual's and the work-arounds skipped on it."""

    def __call__(self, parser: argparse.ArgumentParser, *_args: object, **_kwargs: object) -> None:
        from .ui.textual_fixes import fixes_text

        print(f"console-tui {__version__}\n{fixes_text()}")
        parser.exit()


def build_parser(*, files: bool = True) -> argparse.ArgumentParser:
    """The app's parser; without ``files``, no FILE arguments (for completion, where the
    subcommands take the first word)."""
    parser = argparse.ArgumentParser(
        prog="console-tui",
        description=(
            "A terminal log console for ROS: every node's log messages in one fast table, "
            "with filters, highlights and logger levels."
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=EPILOG,
    )
    parser.add_argument(
        "--version", action=_Version, nargs=0, help="print the version, and the Textual work-arounds in use, and exit"
    )
    if files:
        parser.add_argument(
            "files",
            nargs="*",
            metavar="FILE",
            help=(
                "log files, recordings or folders of them to open, merged by time: rqt_console .csv, .jsonl, "
                "ROS 2 log files and launch logs, ROS 1 rosout.log and run logs, .bag, .mcap, .db3, a rosbag2 "
                "directory, the systemd journal (*.journal, a journal directory); a folder (a ROS 1 run, a ROS 2 "
                "launch, the whole log directory) opens every log in it; journal:, journal:UNIT, journal:PATH "
                "follow the journal live; clickhouse://host:8123/db, clickhouses://..., chdb:///directory "
                "(?table=NAME) read a log warehouse"
            ),
        )
    add_log_format_argument(parser)
    add_last_argument(parser)
    parser.add_argument(
        "--live",
        action="store_true",
        help="with FILEs: show the live log stream too, in the same view (without FILEs it is the default)",
    )
    parser.add_argument(
        "--demo",
        action="store_true",
        help=(
            "start demo nodes in child processes and show their messages: ROS 2 nodes, or with --ros1 "
            "rospy nodes on a roscore of their own (needs ROS 1's roscore and rospy)"
        ),
    )
    parser.add_argument(
        "--demo-domain",
        metavar="N",
        type=domain_id,
        help=(
            "with --demo (ROS 2): the ROS_DOMAIN_ID its nodes run on (default: a domain nothing on this "
            "machine uses, never yours, so that the demo stays out of your graph)"
        ),
    )
    add_ros_version_arguments(parser)
    add_fleet_arguments(parser)
    add_robot_argument(parser)
    add_location_arguments(parser)
    parser.add_argument(
        "--topic",
        metavar="NAME",
        help="log topic to read (default: /rosout_agg when something publishes it, else /rosout)",
    )
    parser.add_argument(
        "--max-messages",
        metavar="N",
        type=positive_int,
        default=DEFAULT_MAX_MESSAGES,
        help=(
            f"messages kept before the oldest are dropped (default {DEFAULT_MAX_MESSAGES:,}): all but the "
            f"newest on disk, in your cache directory; {MEMORY_BOUND:,} at most when they cannot go to disk"
        ),
    )
    parser.add_argument(
        "--keep-history",
        action="store_true",
        help=(
            "keep this session's history when it ends, in the ROS log directory's console-tui-history "
            "(--history opens it again), with the sessions kept before, the oldest going first past --history-size"
        ),
    )
    parser.add_argument(
        "--history-size",
        metavar="MB",
        type=positive_int,
        default=KEPT_BYTES >> 20,
        help=f"with --keep-history: the most the kept history holds, in MB (default {KEPT_BYTES >> 20})",
    )
    parser.add_argument(
        "--history",
        action="store_true",
        help="open the history kept in the ROS log directory (--keep-history), oldest session first",
    )
    parser.add_argument("--utc", action="store_true", help="show times in UTC instead of local time")
    parser.add_argument(
        "--query",
        metavar="QUERY",
        help=(
            "start with this query, for example 'level>=warn node:nav* -node:rviz* +\"failed\"' "
            "(syntax: 'The query line' in the documentation, link below)"
        ),
    )
    parser.add_argument(
        "--rules",
        metavar="FILE",
        help=(
            "start with the exclude and highlight rules saved in this TOML file; "
            "'last' restores the rules in force when console-tui last exited"
        ),
    )
    return parser


def launch_parser() -> argparse.ArgumentParser:
    """``console-tui run [OPTIONS] [--] COMMAND [ARG...]``: the app's options, and a command."""
    parser = build_parser(files=False)
    parser.prog = f"console-tui {RUN}"
    parser.usage = f"console-tui {RUN} [OPTIONS] -- COMMAND [ARG...]"
    parser.description = textwrap.fill(
        "Run a launch (ros2 launch PKG FILE, roslaunch PKG FILE, or any command) in a process group of its own "
        "and show what each of its processes prints, its deaths as errors, with the live log stream (ROS 1 for "
        "roslaunch, ROS 2 for ros2, else as the environment says): a message that arrives both ways shows once. "
        "q or Ctrl+C stops the launch as its terminal's Ctrl+C would (SIGINT, then SIGTERM and SIGKILL).",
        100,
    )
    parser.add_argument("command", nargs=argparse.REMAINDER, metavar="COMMAND", help="the command and its arguments")
    return parser


def completion_parser() -> argparse.ArgumentParser:
    """The app's parser with every subcommand's own parser under it, for shell completion
    (argcomplete); running ``console-tui VERB`` hands the words to the verb's parser instead."""
    parser = build_parser(files=False)
    commands = parser.add_subparsers(dest="verb", metavar="VERB")
    for verb, what in SUBCOMMANDS.items():
        commands.add_parser(verb, help=what)
        commands.choices[verb] = importlib.import_module(f"{__package__}.commands.{verb}").build_parser()
    for alias, verb in ALIASES.items():
        commands.add_parser(alias, help=f"the same as {verb}")
        commands.choices[alias] = commands.choices[verb]
    commands.add_parser(RUN, help="runs a launch and shows what it prints")
    commands.choices[RUN] = launch_parser()
    return parser


def complete() -> None:
    """When a shell asks (argcomplete's ``_ARGCOMPLETE`` in the environment): print the
    completions of its command line and exit; else return at once."""
    if "_ARGCOMPLETE" not in os.environ:
        return
    import argcomplete

    argcomplete.autocomplete(completion_parser())


def add_latest_run(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """``--last``: the newest run's folder (and its ROS 2 nodes' logs) joins ``args.files``;
    no run found exits 2 saying where it looked."""
    from .model.formats import FormatError
    from .model.inert_text import one_line
    from .sources.files import latest_run

    try:
        args.files = [*args.files, *(str(path) for path in latest_run())]
    except FormatError as error:
        parser.error(f"--last: {one_line(str(error))}")


def check_launch(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """``run``'s command into ``args.launch`` (no files); what cannot go with it exits 2."""
    command = list(args.command)
    if command[:1] == ["--"]:
        command = command[1:]
    if not command:
        parser.error("give the command to run after --, for example: console-tui run -- ros2 launch PKG FILE")
    if args.demo or args.robots:
        parser.error("run starts a launch of its own: it cannot be used with --demo, --domain, --master or --fleet")
    args.launch, args.files = command, []


def add_kept_history(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """``--history``: the kept history of the ROS log directory joins ``args.files``."""
    from .ros.log_dir import KEPT_HISTORY, ros_log_dir

    if args.keep_history:
        parser.error("--history opens the kept history: --keep-history with it would keep it twice")
    kept = ros_log_dir() / KEPT_HISTORY
    if not kept.is_dir():
        parser.error(f"--history: no kept history in {kept.parent} (console-tui --keep-history keeps one)")
    args.files = [*args.files, str(kept)]


#: What ``console-tui`` says, and exits 2 with, when there is no terminal to draw on or read keys from.
NOT_A_TERMINAL = (
    "console-tui: not a terminal: the console needs one for its screen and keys (standard input and "
    "standard error).\n"
    "  To print the log stream or log files instead, use 'console-tui tail' (console-tui tail --help)."
)


def on_a_terminal() -> bool:
    """Whether the app can run here: keys come from standard input and the screen goes to
    standard error (Textual's), both a terminal. Under nohup, cron or systemd they are not, and
    the app would read an empty standard input in a loop, a core busy for ever. Another driver
    (``TEXTUAL_DRIVER``: ``console-tui serve``'s browser consoles) needs no terminal."""
    if os.environ.get("TEXTUAL_DRIVER"):
        return True
    try:
        return os.isatty(sys.stdin.fileno()) and os.isatty(sys.stderr.fileno())
    except (AttributeError, OSError, ValueError):  # closed or replaced streams
        return False


def main(argv: Sequence[str] | None = None) -> int:
    """The ``console-tui`` command. ``argv`` None: this process's command line, and a live
    session ends the process itself once everything it started has stopped (see
    ``run_app.end_now``); with ``argv`` given (a caller in the same process), it returns."""
    complete()
    args_list = list(sys.argv[1:] if argv is None else argv)
    if args_list and args_list[0] in SUBCOMMANDS.keys() | ALIASES.keys():
        verb = ALIASES.get(args_list[0], args_list[0])
        module = importlib.import_module(f"{__package__}.commands.{verb}")
        status: int = module.main(args_list[1:])
        return status
    launching = bool(args_list) and args_list[0] == RUN
    parser = launch_parser() if launching else build_parser()
    args_list, file_robots = robot_files(parser, args_list[1:] if launching else args_list)
    args = parser.parse_args(args_list)
    if launching:
        check_launch(parser, args)
    apply_location_arguments(parser, args, follow=True)
    args.file_robots = robots_from_names(args.files, file_robots) if args.robots_from_names else file_robots
    check_rule_arguments(parser, args)
    if args.demo_domain is not None and not args.demo:
        parser.error("--demo-domain goes with --demo")
    check_fleet_arguments(parser, args)
    if args.robots and args.demo:
        parser.error("--demo starts its own nodes: it cannot be used with --domain, --master or --fleet")
    if args.last:
        add_latest_run(parser, args)
    if args.history:
        add_kept_history(parser, args)
    if argv is None and not on_a_terminal():
        print(NOT_A_TERMINAL, file=sys.stderr)
        return EXIT_NO_ROS  # the same status as a missing ROS: this environment cannot run it
    # No collections while start-up makes its objects (a tenth of a second of CPU before the
    # first frame, measured): the app collects once and freezes them after its first frame
    # (ui.gc_policy), where the collector is on again.
    gc.disable()
    try:
        from .run_app import run_app

        return run_app(args, end_process=argv is None)
    finally:
        gc.enable()


if __name__ == "__main__":
    raise SystemExit(main())
