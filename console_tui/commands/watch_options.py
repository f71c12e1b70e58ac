"""``ros2 log watch``'s options for ``console-tui tail`` (ros2cli 0.42, REP-0156), so that a
ROS user's ``--level/--logger/--regex/--no-timestamp`` work here too: each becomes a term
of the query the rest of ``tail`` applies, or the default line without its time."""

from __future__ import annotations

import argparse
import re

from ..model.formats.rcutils_log import DEFAULT_TEMPLATE
from ..model.levels import parse_severity

#: The default line with ``--no-timestamp``.
NO_TIMESTAMP_TEMPLATE = DEFAULT_TEMPLATE.replace(" [{time}]", "")
#: A logger (node) name or glob as ``--logger`` takes it: what ROS names and globs are made of.
_LOGGER_NAME = re.compile(r"[A-Za-z0-9_./*?~-]+")


def add_watch_arguments(parser: argparse.ArgumentParser) -> None:
    """``ros2 log watch``'s filter options (``--no-color`` sits with ``--color``)."""
    group = parser.add_argument_group("as 'ros2 log watch' takes them (each adds to --query)")
    group.add_argument("--level", metavar="LEVEL", help="this severity and worse: query 'level>=LEVEL'")
    group.add_argument("--logger", metavar="NAME", help="this logger (node) name or glob: query 'node:NAME'")
    group.add_argument("--regex", metavar="REGEX", help="messages that match this regular expression: query '/REGEX/'")
    group.add_argument(
        "--no-timestamp", action="store_true", help="the default line without its time (not with --format or --json)"
    )


def apply_watch_arguments(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Fold ``--level/--logger/--regex`` into ``args.query`` (before it is compiled), and
    ``--no-timestamp`` into ``args.format``; a bad value exits 2 naming its option."""
    terms: list[str] = []
    if args.level is not None:
        try:
            terms.append(f"level>={parse_severity(args.level).name.lower()}")
        except ValueError as error:
            parser.error(f"--level: {error}")
    if args.logger is not None:
        if not _LOGGER_NAME.fullmatch(args.logger):
            parser.error(f"--logger: not a logger name or glob: {args.logger!r}")
        terms.append(f"node:{args.logger}")
    if args.regex is not None:
        try:
            re.compile(args.regex)
        except re.error as error:
            parser.error(f"--regex: not a regular expression ({error}): {args.regex!r}")
        terms.append("/" + args.regex.replace("/", "\\/") + "/")
    if terms:
        args.query = " ".join([*terms, *([args.query] if args.query else [])])
    if args.no_timestamp:
        if args.format is not None or args.json:
            parser.error("--no-timestamp: only with the default line (give a --format without {time})")
        args.format = NO_TIMESTAMP_TEMPLATE
