"""``console-tui tail``: log messages on standard output, filtered with the app's rules.

Live (the app's live stream: ``/rosout_agg`` when something publishes it, else
``/rosout``) or from files (any format the app opens, merged by time), or both; with
``--follow``, text files are followed as they grow (and when they are rotated). Lines
are printed as ROS prints them (``--format``), or as JSON (``--json``). Message text never
reaches the terminal raw: control characters, escape sequences and bidi overrides are
printed as visible stand-ins, and in JSON as ``\\u`` escapes.

A closed pipe (``console-tui tail | head -1``) ends it quietly with status 0.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
from collections.abc import Iterable, Sequence
from typing import BinaryIO, cast

from ..model.formats import FormatError
from ..model.formats.print_format import ROBOT_PREFIX, PrintFormat, TemplateError, json_text
from ..model.formats.rcutils_log import DEFAULT_TEMPLATE
from ..model.inert_text import one_line
from ..model.levels import parse_severity
from ..model.rules.ruleset import Decoration, RuleSet
from ..model.rules.stream import StreamFilter
from ..model.store.intake_queue import IntakeQueue
from ..model.store.record import LogRecord
from ..sources.files import LogFile, TextLogFile, latest_run, load_records, open_logs
from ..sources.files.follow import FollowedFile
from ..sources.journal.journal_location import journal_location
from ..sources.journal.journalctl import JournalUnavailable, find_journalctl, local_journal_problem
from ..sources.live import LiveIntake, RosUnavailable, open_journal, open_stream
from ..system.signal_stop import SignalStop
from .arguments import (
    EXIT_NO_ROS,
    add_fleet_arguments,
    add_last_argument,
    add_log_format_argument,
    add_ros_version_arguments,
    check_fleet_arguments,
    check_rule_arguments,
    command_parser,
)
from .closed_pipe import quiet_stdout, reader_gone
from .live_reports import LiveReports
from .location_options import add_location_arguments, apply_location_arguments
from .warehouse_windows import Windows, merged
from .watch_options import add_watch_arguments, apply_watch_arguments

EXIT_OK = 0
EXIT_FILES = 1
EXIT_USAGE = 2

#: How often followed files and the live queue are looked at.
POLL_S = 0.1
FORMAT_VARIABLE = "RCUTILS_CONSOLE_OUTPUT_FORMAT"


EPILOG = f"""--format tokens, mixed as you like (\\n and \\t are decoded):
  ROS 2 (RCUTILS_CONSOLE_OUTPUT_FORMAT): {{severity}} {{name}} {{message}} {{time}}
      {{time_as_nanoseconds}} {{date_time_with_ms}} {{file_name}} {{function_name}} {{line_number}}
  ROS 1 (ROSCONSOLE_FORMAT): ${{severity}} ${{time}} ${{time:%H:%M:%S}} ${{walltime}} ${{node}}
      ${{logger}} ${{message}} ${{file}} ${{function}} ${{line}}

exit status:
  {EXIT_OK}  done, stopped by Ctrl-C, or the pipe closed
  {EXIT_FILES}  a FILE could not be read
  {EXIT_USAGE}  bad command line, or ROS is not available for the live stream (the same number in every command)"""


def build_parser() -> argparse.ArgumentParser:
    parser = command_parser(
        "tail",
        "Print log messages on standard output, filtered with the app's query language and rule "
        "files: the live stream of ROS 2 or ROS 1 (without FILEs: /rosout_agg when something publishes "
        "it, else /rosout), "
        "or log files and recordings merged by time, or both (--live). Runs until Ctrl-C when live or "
        "following; a closed pipe (| head) ends it quietly.",
        EPILOG,
    )
    parser.add_argument(
        "files",
        nargs="*",
        metavar="FILE",
        help="log files, recordings, or folders of them (any format the app opens; a folder: every log in it), "
        "or a log warehouse: clickhouse://host:8123/db, clickhouses://..., chdb:///directory (?table=NAME)",
    )
    add_last_argument(parser)
    parser.add_argument("--live", action="store_true", help="with FILEs: the live stream too, after them")
    parser.add_argument(
        "-f", "--follow", action="store_true", help="keep reading text FILEs as they grow (and when rotated)"
    )
    parser.add_argument("--topic", metavar="NAME", help="live: the log topic (default /rosout_agg if published)")
    add_ros_version_arguments(parser)
    add_fleet_arguments(parser)
    parser.add_argument(
        "--query", metavar="QUERY", help="print only what this query shows, for example 'level>=warn -node:rviz*'"
    )
    parser.add_argument(
        "--rules", metavar="FILE", help="apply the rules saved in this TOML file ('last': those the app last had)"
    )
    output = parser.add_mutually_exclusive_group()
    output.add_argument(
        "--format",
        metavar="FMT",
        help="how to print each message (default: $RCUTILS_CONSOLE_OUTPUT_FORMAT, else "
        "'[{severity}] [{time}] [{name}]: {message}'); tokens below",
    )
    output.add_argument(
        "--json",
        action="store_true",
        help="one JSON object a line: stamp_ns, level, node, msg, file, function, line (and robot, of a fleet)",
    )
    colour = parser.add_mutually_exclusive_group()
    colour.add_argument(
        "--color",
        choices=("auto", "always", "never"),
        default="auto",
        help="colour by severity: auto (on a terminal, and NO_COLOR not set) by default; always and never win over NO_COLOR",
    )
    colour.add_argument("--no-color", dest="color", action="store_const", const="never", help="same as --color never")
    parser.add_argument("--utc", action="store_true", help="dates and query times in UTC rather than local time")
    add_log_format_argument(parser)
    add_watch_arguments(parser)
    add_location_arguments(parser, window_rows=True)
    return parser


class PipeClosed(Exception):
    """Standard output's reader went away."""


class Printer:
    """Writes filtered records to a binary stream, one batch at a time, flushed."""

    def __init__(self, stream: BinaryIO, line: PrintFormat | None) -> None:
        self.stream = stream
        self.line = line
        self.printed = 0

    def write(self, items: Iterable[tuple[LogRecord, Decoration]]) -> None:
        line = self.line
        if line is None:
            texts = [json_text(record) for record, _ in items]
        else:
            texts = [line.text(record, decoration) for record, decoration in items]
        if not texts:
            return
        try:
            self.stream.write(("\n".join(texts) + "\n").encode("utf-8", "replace"))
            self.stream.flush()
        except (BrokenPipeError, ConnectionResetError):
            raise PipeClosed from None
        self.printed += len(texts)

    def check_reader(self) -> None:
        """``PipeClosed`` when nobody reads the stream any more, though nothing was written."""
        try:
            fd = self.stream.fileno()
        except (AttributeError, OSError, ValueError):
            return
        if reader_gone(fd):
            raise PipeClosed


def use_color(choice: str, stream: object, environ: dict[str, str] | os._Environ[str]) -> bool:
    """Colour for ``--color choice``: always or never as asked (a flag wins over the
    environment, as no-color.org says); auto: not with NO_COLOR set (to anything but ""),
    else when the stream is a terminal that is not 'dumb'."""
    if choice != "auto":
        return choice == "always"
    if environ.get("NO_COLOR"):
        return False
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty()) and environ.get("TERM", "") != "dumb"


def main(argv: Sequence[str]) -> int:
    parser = build_parser()
    args = parser.parse_args(list(argv))
    apply_watch_arguments(parser, args)
    check_rule_arguments(parser, args)
    check_fleet_arguments(parser, args)
    if args.last:
        try:
            args.files = [*args.files, *(str(path) for path in latest_run())]
        except FormatError as error:
            parser.error(f"--last: {one_line(str(error))}")
    apply_location_arguments(parser, args, follow=True)
    if args.follow:  # a journal file or directory is followed by journalctl itself
        journals = [(path, journal_location(path)) for path in args.files]
        args.journals += [found.query(follow=True) for _, found in journals if found is not None]
        args.files = [path for path, found in journals if found is None]
    if args.follow and not (args.files or args.journals or args.warehouses):
        parser.error("--follow needs FILEs to follow (the live stream is followed anyway)")
    problem = _journal_problem(args.journals)
    if problem:
        print(f"console-tui tail: {problem}", file=sys.stderr)
        return EXIT_NO_ROS  # not available here, as a missing ROS is
    rules = (args.rule_set or RuleSet()).with_query(args.query_entries)
    line: PrintFormat | None = None
    if not args.json:
        template = args.format if args.format is not None else (os.environ.get(FORMAT_VARIABLE) or None)
        if (args.robots or args.warehouses) and "{robot}" not in (template or ""):  # a fleet's lines say their robot
            template = ROBOT_PREFIX + (template or DEFAULT_TEMPLATE)
        try:
            color = use_color(args.color, sys.stdout, os.environ)
            line = PrintFormat(template, utc=args.utc, color=color, strict=args.format is not None)
        except TemplateError as error:
            parser.error(f"--format: {error}" if args.format is not None else f"${FORMAT_VARIABLE}: {error}")
    stream = cast(BinaryIO, getattr(sys.stdout, "buffer", sys.stdout))
    run = _Run(Printer(stream, line), StreamFilter(rules), rules)
    previous = {sig: signal.signal(sig, run.stop.on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        return run.main(args)
    except PipeClosed:
        quiet_stdout()
        return EXIT_OK
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)


class _Run:
    def __init__(self, printer: Printer, stream_filter: StreamFilter, rules: RuleSet) -> None:
        self.printer = printer
        self.rules = rules
        self.filter = stream_filter
        self.stop = SignalStop()
        self.status = EXIT_OK
        self.queue = IntakeQueue()
        #: Problems already printed, per file (by id).
        self._told: dict[int, int] = {}

    def print(self, batch: list[LogRecord]) -> None:
        self.printer.write(self.filter.filter(batch))
        for rule, why in self.filter.switched_off:
            _complain(f"rule switched off, {why}: {rule.describe()}")
        self.filter.switched_off.clear()

    def main(self, args: argparse.Namespace) -> int:
        lives: list[LiveIntake] = []
        # --level is asked of the middleware too (a DDS content filter, as ros2 log watch asks).
        min_level = int(parse_severity(args.level)) if args.level is not None else 0
        if args.robots or args.live or not (args.files or args.journals or args.warehouses):
            try:
                lives = open_stream(self.queue, args.robots, topic=args.topic, ros=args.ros, min_level=min_level)
            except RosUnavailable as error:
                print(f"console-tui tail: {error}", file=sys.stderr)
                return EXIT_NO_ROS
        lives += [open_journal(self.queue, query, log_format=args.log_format or "") for query in args.journals]
        windows = Windows(args, self.rules, _complain, max_rows=args.max_messages)
        try:
            followed: list[FollowedFile] = []
            if args.files or args.warehouses:
                followed = self.files(args, windows)
            for live in lives:
                live.source.start()
            if lives or followed or (args.follow and windows.readers):
                self.keep_reading(followed, lives, windows if args.follow else None)
        finally:
            windows.close()
            for live in lives:
                live.close()
        if windows.failed:
            self.status = EXIT_FILES
        return self.status

    def files(self, args: argparse.Namespace, windows: Windows) -> list[FollowedFile]:
        """Print the files and the warehouse's windows merged by time; the text files to go on
        following, if asked."""
        opened = open_logs(args.files, log_format=args.log_format)
        files = opened.files
        for problem in opened.failures:
            _complain(str(problem))
            self.status = EXIT_FILES
        followed: list[FollowedFile] = []
        try:
            if args.follow:
                followed = [FollowedFile(f) for f in files if isinstance(f, TextLogFile)]
                once: list[LogFile] = [f for f in files if not isinstance(f, TextLogFile)]
                streams = [f.records_so_far() for f in followed] + [f.batches(self.stop) for f in once]
                batches = merged([*streams, *windows.streams()])
            else:
                batches = merged([load_records(files, self.stop), *windows.streams()])
            for batch in batches:
                self.print(batch)
                if self.stop.is_set():
                    break
        finally:
            for file in files:
                file.close()
        self._problems(files)
        return followed

    def keep_reading(
        self, followed: list[FollowedFile], lives: Sequence[LiveIntake], windows: Windows | None = None
    ) -> None:
        reports = LiveReports(lives, _complain)
        try:
            while not self.stop.wait(POLL_S):
                self.printer.check_reader()
                if followed:
                    batch = [record for f in followed for record in f.read()]
                    batch.sort(key=_stamp)
                    self.print(batch)
                    self._problems(followed)
                if lives:
                    self.print(self.queue.drain())
                if windows is not None:
                    self.print(windows.newer())
                reports.tell()
                if lives and not followed and windows is None and all(_ended(live) for live in lives):
                    self.status = EXIT_FILES  # the journal could not be read (said above)
                    break
        finally:
            for f in followed:
                f.close()

    def _problems(self, files: Sequence[LogFile | FollowedFile]) -> None:
        for file in files:
            items = file.problems.items
            for problem in items[self._told.get(id(file), 0) :]:
                _complain(str(problem))
            self._told[id(file)] = len(items)


def _journal_problem(queries: Sequence) -> str:
    """Why the journal asked for cannot be read here (no journalctl, no journal), or ""."""
    if not queries:
        return ""
    try:
        find_journalctl()
    except JournalUnavailable as error:
        return str(error)
    return next((local_journal_problem() for query in queries if query.local and local_journal_problem()), "")


def _ended(live: LiveIntake) -> bool:
    """A journal source whose journalctl ended with a problem (a ROS source never ends)."""
    status = live.source.status
    return getattr(live.source, "kind", "") == "journal" and bool(status.problem) and not status.running


def _stamp(record: LogRecord) -> int:
    return record.stamp_ns


def _complain(text: str) -> None:
    print(f"console-tui tail: {one_line(text, 500)}", file=sys.stderr, flush=True)
