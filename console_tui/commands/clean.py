"""``console-tui clean check|purge``: rosclean for ROS 2 and ROS 1 log directories.

``check`` prints the size of the log directory and its largest runs; ``purge`` removes
runs (all of them, those older than an age, or the oldest until the rest fits a size)
after asking, unless ``--yes``. What counts as a run, and how removal stays inside the
directory, is in ``console_tui.sources.log_dir``.
"""

from __future__ import annotations

import argparse
import sys
import textwrap
import time
from collections.abc import Sequence
from datetime import datetime
from pathlib import Path

from ..model.rules.query import QueryError, parse_time
from ..model.text import plural
from ..sources.log_dir import LogRun, UnsafeRemoval, dangling_links, remove_run, ros_log_dir, scan_runs
from .arguments import add_subcommand, command_parser, parse_size, size_text

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_USAGE = 2
EXIT_DECLINED = 3

EXIT_CODES = f"""exit status:
  {EXIT_OK}  done (or nothing to do)
  {EXIT_FAILED}  some runs could not be removed (each is named on stderr)
  {EXIT_USAGE}  bad command line
  {EXIT_DECLINED}  purge: not confirmed"""

DEFAULT_TOP = 10


def build_parser() -> argparse.ArgumentParser:
    parser = command_parser(
        "clean",
        "rosclean for ROS 2 and ROS 1: check the size of the ROS log directory "
        "($ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log) and purge old runs. A run is one "
        "entry of the directory: a ROS 1 run, a ros2 launch directory, a console-tui rosout "
        "directory, or one ROS 2 node's log file. Symlinks are never followed.",
        EXIT_CODES,
    )
    commands = parser.add_subparsers(dest="command", required=True, metavar="{check,purge}")
    check = add_subcommand(
        commands,
        "check",
        "size of the log directory and its largest runs",
        description="Print the size of the ROS log directory and its largest runs.",
        epilog=EXIT_CODES,
    )
    check.add_argument("--top", type=int, default=DEFAULT_TOP, metavar="N", help=f"runs listed (default {DEFAULT_TOP})")
    purge = add_subcommand(
        commands,
        "purge",
        "remove runs: all, --older-than AGE, or the oldest down to --keep-size SIZE",
        description=textwrap.fill(
            "Remove runs from the ROS log directory: all of them, or those last written before "
            "--older-than, and/or the oldest ones until what is left fits in --keep-size. Lists what "
            "it will remove and asks first, unless --yes."
        ),
        epilog=EXIT_CODES,
    )
    purge.add_argument(
        "--older-than",
        metavar="AGE",
        help="only runs last written longer ago than this: 90m, 12h, 7d, or a date such as 2026-11-01",
    )
    purge.add_argument(
        "--keep-size",
        metavar="SIZE",
        type=parse_size,
        help="remove the oldest runs until the rest takes at most SIZE: 500M, 1G, 1.5G (powers of 1024)",
    )
    purge.add_argument("-y", "--yes", action="store_true", help="do not ask")
    for sub in (check, purge):
        sub.add_argument("--dir", metavar="DIR", help="the log directory (default: where ROS writes its logs)")
    return parser


def main(argv: Sequence[str]) -> int:
    parser = build_parser()
    args = parser.parse_args(list(argv))
    log_dir = Path(args.dir) if args.dir else ros_log_dir()
    if args.command == "check":
        return check(log_dir, args.top)
    cutoff = None
    if args.older_than:
        try:
            cutoff = parse_time(args.older_than) / 1e9
        except QueryError as error:
            parser.error(f"--older-than: {error.reason}")
    return purge(log_dir, cutoff=cutoff, keep_size=args.keep_size, confirmed=args.yes)


def check(log_dir: Path, top: int) -> int:
    runs = scan_runs(log_dir)
    if not log_dir.is_dir():
        print(f"{log_dir}: no log directory (nothing to clean)")
        return EXIT_OK
    total = sum(run.size for run in runs)
    real = log_dir.resolve()
    shown = f"{log_dir} (-> {real})" if real != log_dir.absolute() else str(log_dir)
    print(f"{shown}: {size_text(total)} in {plural(len(runs), 'run')}")
    largest = sorted((run for run in runs if run.type != "symlink"), key=lambda run: -run.size)[: max(top, 0)]
    if largest:
        print("Largest runs:" if len(largest) > 1 else "Largest run:")
    for run in largest:
        print(_run_line(run))
    return EXIT_OK


def select(runs: Sequence[LogRun], *, cutoff: float | None, keep_size: int | None) -> list[LogRun]:
    """The runs to remove, oldest first. With neither limit: all of them, symlinks too.
    Otherwise symlinks are left (those left pointing at nothing go afterwards)."""
    if cutoff is None and keep_size is None:
        return list(runs)
    candidates = sorted((run for run in runs if run.type != "symlink"), key=lambda run: (run.mtime, run.name))
    chosen = [run for run in candidates if cutoff is not None and run.mtime < cutoff]
    if keep_size is not None:
        left = sum(run.size for run in candidates) - sum(run.size for run in chosen)
        for run in candidates:
            if left <= keep_size:
                break
            if run not in chosen:
                chosen.append(run)
                left -= run.size
    return sorted(chosen, key=lambda run: (run.mtime, run.name))


def purge(log_dir: Path, *, cutoff: float | None, keep_size: int | None, confirmed: bool) -> int:
    if not log_dir.is_dir():
        print(f"{log_dir}: no log directory (nothing to clean)")
        return EXIT_OK
    runs = scan_runs(log_dir)
    chosen = select(runs, cutoff=cutoff, keep_size=keep_size)
    if not chosen:
        print(f"{log_dir}: nothing to remove ({size_text(sum(r.size for r in runs))} in {plural(len(runs), 'run')})")
        return EXIT_OK
    freed = sum(run.size for run in chosen)
    for run in chosen:
        print(_run_line(run))
    question = f"Remove these {plural(len(chosen), 'run')} ({size_text(freed)}) from {log_dir}?"
    if not confirmed and not _ask(question):
        print("Nothing removed.", file=sys.stderr)
        return EXIT_DECLINED
    failed = 0
    for run in chosen:
        try:
            remove_run(log_dir, run)
        except (UnsafeRemoval, OSError) as error:
            failed += 1
            print(f"console-tui clean: {run.name}: not removed: {_reason(error)}", file=sys.stderr)
    for link in dangling_links(log_dir):
        try:
            remove_run(log_dir, link)
        except (UnsafeRemoval, OSError):
            pass
    removed = len(chosen) - failed
    print(f"Removed {plural(removed, 'run')} ({size_text(freed)} before any failures) from {log_dir}.")
    return EXIT_FAILED if failed else EXIT_OK


def _ask(question: str) -> bool:
    if not sys.stdin or not sys.stdin.isatty():
        print(f"{question} Not asked: standard input is not a terminal; pass --yes.", file=sys.stderr)
        return False
    try:
        answer = input(f"{question} [y/N] ")
    except EOFError:
        return False
    return answer.strip().lower() in ("y", "yes")


def _run_line(run: LogRun) -> str:
    when = datetime.fromtimestamp(run.mtime).strftime("%Y-%m-%d %H:%M")
    age = _age(time.time() - run.mtime)
    return f"{size_text(run.size):>6}  {when} ({age:>3} ago)  {run.kind:<18}  {run.name}"


def _age(seconds: float) -> str:
    for unit, length in (("d", 86400), ("h", 3600), ("m", 60)):
        if seconds >= length:
            return f"{int(seconds // length)}{unit}"
    return f"{max(int(seconds), 0)}s"


def _reason(error: BaseException) -> str:
    if isinstance(error, OSError):
        return error.strerror or str(error)
    return str(error)
