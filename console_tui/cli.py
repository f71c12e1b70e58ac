"""The ``console-tui`` command line."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from . import __version__
from .commands.arguments import add_log_format_argument, positive_int
from .model.store import DEFAULT_MAX_MESSAGES


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="console-tui",
        description=(
            "A terminal log console for ROS: every node's log messages in one fast table, "
            "with filters, highlights and logger levels."
        ),
        epilog=(
            "Subcommands: 'console-tui loggers --help' lists and sets logger levels without the TUI; "
            "'console-tui convert --help' converts log files and recordings."
        ),
    )
    parser.add_argument("--version", action="version", version=f"console-tui {__version__}")
    parser.add_argument(
        "files",
        nargs="*",
        metavar="FILE",
        help=(
            "log files or recordings to open, merged by time: rqt_console .csv, .jsonl, ROS 2 log files "
            "(~/.ros/log), ROS 1 rosout.log, .bag, .mcap, .db3 or a rosbag2 directory"
        ),
    )
    add_log_format_argument(parser)
    parser.add_argument(
        "--live",
        action="store_true",
        help="with FILEs: show the live log stream too, in the same view (without FILEs it is the default)",
    )
    parser.add_argument(
        "--demo",
        action="store_true",
        help="start demo ROS 2 nodes in child processes and show their messages",
    )
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
        help=f"messages kept before the oldest are dropped (default {DEFAULT_MAX_MESSAGES:,})",
    )
    parser.add_argument("--utc", action="store_true", help="show times in UTC instead of local time")
    parser.add_argument(
        "--query",
        metavar="QUERY",
        help=(
            "start with this query, for example 'level>=warn node:nav* -node:rviz* +\"failed\"' (syntax: docs/rules.md)"
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


def check_rule_arguments(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Compile ``--query`` and read ``--rules`` before the app starts; a problem exits 2.

    Sets ``args.query_entries`` (the query's rule entries, or ``()``) and ``args.rule_set``
    (the file's ``RuleSet``, or None).
    """
    from .model.rules.query import QueryError, caret_line, parse_query
    from .model.rules.rule import RuleError
    from .model.rules.rulesfile import last_rules_path, load_rules
    from .model.text import one_line

    args.query_entries = ()
    args.rule_set = None
    if args.query:
        try:
            args.query_entries = parse_query(args.query, utc=args.utc)
        except QueryError as error:
            parser.error(f"--query is not valid (at {error.position + 1}):\n{caret_line(one_line(args.query), error)}")
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


def main(argv: Sequence[str] | None = None) -> int:
    args_list = list(sys.argv[1:] if argv is None else argv)
    if args_list[:1] == ["loggers"]:
        from .commands.loggers import main as loggers_main

        return loggers_main(args_list[1:])
    if args_list[:1] == ["convert"]:
        from .commands.convert import main as convert_main

        return convert_main(args_list[1:])
    parser = build_parser()
    args = parser.parse_args(args_list)
    check_rule_arguments(parser, args)
    from .launch import run_app

    return run_app(args)


if __name__ == "__main__":
    raise SystemExit(main())
