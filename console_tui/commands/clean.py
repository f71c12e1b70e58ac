"""``console-tui clean check|purge``: rosclean for ROS 2 and ROS 1 log directories.

``check`` prints the size of the log directory and its largest runs; ``purge`` removes
runs (all of them, those older than an age, or the oldest until the rest fits a size)
after asking, unless ``--yes``. What counts as a run, and how removal stays inside the
directory, is in ``console_tui.ros.log_dir``.
"""

from __future__ import annotations

import argparse
import sys
import textwrap
import time
from collections.abc import Sequence
from datetime import datetime
from pathlib import Path

from ..model.inert_text import one_line, plural
from ..model.rules.query import QueryError, parse_time
from ..ros.log_dir import (
    LogRun,
    UnsafeRemoval,
    dangling_links,
    foreign_entries,
    is_ros_entry,
    refused_log_dir,
    remove_run,
    ros_log_dir,
    scan_runs,
)
from .arguments import add_subcommand, command_parser, parse_size, size_text

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_USAGE = 2
EXIT_DECLINED = 3

_CHECK_CODES = f"""  {EXIT_OK}  done (or no log directory)
  {EXIT_FAILED}  refused: the directory is /, the home directory or above it
  {EXIT_USAGE}  bad command line"""
_PURGE_CODES = f"""  {EXIT_OK}  done (or nothing to do)
  {EXIT_FAILED}  some runs could not be removed (each is named on stderr), or the directory
     was refused: /, the home directory or above it, or (without --force) it holds
     entries that are not ROS logs
  {EXIT_USAGE}  bad command line
  {EXIT_DECLINED}  not confirmed"""
CHECK_EXIT_CODES = "exit status:\n" + _CHECK_CODES
PURGE_EXIT_CODES = "exit status:\n" + _PURGE_CODES
EXIT_CODES = f"exit status of check:\n{_CHECK_CODES}\nexit status of purge:\n{_PURGE_CODES}"

#: A run written to this recently is taken as still being written: ``--keep-size`` leaves it.
ACTIVE_S = 60.0
DEFAULT_TOP = 10


def build_parser() -> argparse.ArgumentParser:
    parser = command_parser(
        "clean",
        "rosclean for ROS 2 and ROS 1: check the size of the ROS log directory "
        "($ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log) and purge old runs. A run is one "
        "entry of the directory: a ROS 1 run, a ros2 launch directory, a console-tui rosout "
        "directory, or one ROS 2 node's log file; purge removes nothing else, and refuses a "
        "directory holding anything else (unless --force), /, and the home directory. "
        "Symlinks are never followed.",
        EXIT_CODES,
    )
    commands = parser.add_subparsers(dest="command", required=True, metavar="{check,purge}")
    check = add_subcommand(
        commands,
        "check",
        "size of the log directory and its largest runs",
        description="Print the size of the ROS log directory and its largest runs.",
        epilog=CHECK_EXIT_CODES,
    )
    check.add_argument("--top", type=int, default=DEFAULT_TOP, metavar="N", help=f"runs listed (default {DEFAULT_TOP})")
    purge = add_subcommand(
        commands,
        "purge",
        "remove runs: all, --older-than AGE, or the oldest down to --keep-size SIZE",
        description=textwrap.fill(
            "Remove runs from the ROS log directory: all of them, or those last written before "
            "--older-than, and/or the oldest ones until what is left fits in --keep-size. Lists what "
            "it will remove and asks first, unless --yes. Only ROS logs are removed (by their "
            "shape); a directory holding anything else is refused unless --force."
        ),
        epilog=PURGE_EXIT_CODES,
    )
    purge.add_argument(
        "--older-than",
        metavar="AGE",
        type=_cutoff,
        help="only runs last written longer ago than this: 90m, 12h, 7d, or a date such as 2026-11-01",
    )
    purge.add_argument(
        "--keep-size",
        metavar="SIZE",
        type=parse_size,
        help="remove the oldest runs until the rest takes at most SIZE: 500M, 1G, 1.5G (powers of 1024); "
        f"runs written in the last {ACTIVE_S:g} s are kept",
    )
    purge.add_argument("-y", "--yes", action="store_true", help="do not ask")
    purge.add_argument(
        "--force",
        action="store_true",
        help="purge even when the directory holds entries that are not ROS logs (those are left alone)",
    )
    for sub in (check, purge):
        sub.add_argument("--dir", metavar="DIR", help="the log directory (default: where ROS writes its logs)")
    return parser


def _cutoff(text: str) -> float:
    try:
        return parse_time(text) / 1e9
    except QueryError as error:
        raise argparse.ArgumentTypeError(error.reason) from None


def main(argv: Sequence[str]) -> int:
    parser = build_parser()
    args = parser.parse_args(list(argv))
    log_dir = Path(args.dir) if args.dir else ros_log_dir()
    refused = refused_log_dir(log_dir)
    if refused:
        print(f"console-tui clean: {one_line(refused)}: nothing done (set ROS_LOG_DIR or pass --dir)", file=sys.stderr)
        return EXIT_FAILED
    if args.command == "check":
        return check(log_dir, args.top)
    return purge(log_dir, cutoff=args.older_than, keep_size=args.keep_size, confirmed=args.yes, force=args.force)


def _where(log_dir: Path) -> str:
    """The directory as named, and where it really is when that differs."""
    real = log_dir.resolve()
    return one_line(f"{log_dir} (-> {real})" if real != log_dir.absolute() else str(log_dir))


def _runs_text(runs: Sequence[LogRun]) -> str:
    """``2.9M in 3 runs``: the runs listed, never the ``latest`` link."""
    counted = [run for run in runs if run.type != "symlink"]
    return f"{size_text(sum(run.size for run in counted))} in {plural(len(counted), 'run')}"


def _others_text(others: Sequence[LogRun]) -> str:
    names = ", ".join(one_line(run.name, 60) for run in others[:5]) + (", …" if len(others) > 5 else "")
    what = "that is not a ROS log" if len(others) == 1 else "that are not ROS logs"
    return f"{plural(len(others), 'entry', 'entries')} {what} ({names})"


def check(log_dir: Path, top: int) -> int:
    if not log_dir.is_dir():
        print(f"{one_line(str(log_dir))}: no log directory (nothing to clean)")
        return EXIT_OK
    runs = scan_runs(log_dir.resolve())
    ours = [run for run in runs if is_ros_entry(run)]
    print(f"{_where(log_dir)}: {_runs_text(ours)}")
    others = foreign_entries(runs)
    if others:
        print(f"Also {_others_text(others)}: never removed.")
    largest = sorted((run for run in ours if run.type != "symlink"), key=lambda run: -run.size)[: max(top, 0)]
    if largest:
        print("Largest runs:" if len(largest) > 1 else "Largest run:")
    for run in largest:
        print(_run_line(run))
    return EXIT_OK


def select(
    runs: Sequence[LogRun], *, cutoff: float | None, keep_size: int | None, now: float | None = None
) -> list[LogRun]:
    """The runs to remove, oldest first. With neither limit: all of them, symlinks too.
    Otherwise symlinks are left (those left pointing at nothing go afterwards), and
    ``keep_size`` never takes a run written in the last ``ACTIVE_S``."""
    if cutoff is None and keep_size is None:
        return list(runs)
    candidates = sorted((run for run in runs if run.type != "symlink"), key=lambda run: (run.mtime, run.name))
    chosen = [run for run in candidates if cutoff is not None and run.mtime < cutoff]
    if keep_size is not None:
        active_since = (time.time() if now is None else now) - ACTIVE_S
        left = sum(run.size for run in candidates) - sum(run.size for run in chosen)
        for run in candidates:
            if left <= keep_size:
                break
            if run not in chosen and run.mtime < active_since:
                chosen.append(run)
                left -= run.size
    return sorted(chosen, key=lambda run: (run.mtime, run.name))


def purge(log_dir: Path, *, cutoff: float | None, keep_size: int | None, confirmed: bool, force: bool = False) -> int:
    if not log_dir.is_dir():
        print(f"{one_line(str(log_dir))}: no log directory (nothing to clean)")
        return EXIT_OK
    where = _where(log_dir)
    real = log_dir.resolve()  # scanned and removed from by its real path: a link moved meanwhile changes nothing
    runs = scan_runs(real)
    others = foreign_entries(runs)
    if others and not force:
        print(
            f"console-tui clean: {where} holds {_others_text(others)}: not a log directory, nothing removed "
            "(--force removes only the ROS logs in it)",
            file=sys.stderr,
        )
        return EXIT_FAILED
    ours = [run for run in runs if is_ros_entry(run)]
    chosen = select(ours, cutoff=cutoff, keep_size=keep_size)
    if not chosen:
        print(f"{where}: nothing to remove ({_runs_text(ours)})")
        return EXIT_OK
    for run in chosen:
        print(_run_line(run))
    size = size_text(sum(run.size for run in chosen))
    if not confirmed and not _ask(f"Remove {_these(chosen)} ({size}) from {where}?"):
        print("Nothing removed.", file=sys.stderr)
        return EXIT_DECLINED
    removed: list[LogRun] = []
    for run in chosen:
        try:
            remove_run(real, run)
        except (UnsafeRemoval, OSError) as error:
            print(f"console-tui clean: {one_line(run.name)}: not removed: {one_line(_reason(error))}", file=sys.stderr)
        else:
            removed.append(run)
    for link in dangling_links(real):
        try:
            remove_run(real, link)
        except (UnsafeRemoval, OSError):
            pass
    freed = size_text(sum(run.size for run in removed))
    if len(removed) == len(chosen):
        print(f"Removed {_these(removed, this=False)} ({freed}) from {where}.")
        return EXIT_OK
    failed = len(chosen) - len(removed)
    print(f"Removed {_these(removed, this=False)} ({freed}) from {where}; {failed:,} could not be removed.")
    return EXIT_FAILED


def _these(runs: Sequence[LogRun], *, this: bool = True) -> str:
    """``this run``, ``these 3 runs and 1 link`` (``1 run`` without ``this``): links are no runs."""
    count = sum(1 for run in runs if run.type != "symlink")
    links = len(runs) - count
    if this:
        text = "this run" if count == 1 else f"these {plural(count, 'run')}"
    else:
        text = plural(count, "run")
    return text + (f" and {plural(links, 'link')}" if links else "")


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
    return f"{size_text(run.size):>6}  {when} ({age:>3} ago)  {run.kind:<18}  {one_line(run.name)}"


def _age(seconds: float) -> str:
    for unit, length in (("d", 86400), ("h", 3600), ("m", 60)):
        if seconds >= length:
            return f"{int(seconds // length)}{unit}"
    return f"{max(int(seconds), 0)}s"


def _reason(error: BaseException) -> str:
    if isinstance(error, OSError):
        return error.strerror or str(error)
    return str(error)
