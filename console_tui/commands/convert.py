"""``console-tui convert IN... -o OUT``: log files and recordings to one saved file.

Exit status: 0 when every input was read without a problem; 1 when the output was
written but something was wrong (an input could not be opened, bad lines, a truncated
file, an input without log records: each listed on stderr); 2 when nothing was written
(bad usage, no input gave a single record, or the output cannot be written).
"""

from __future__ import annotations

import argparse
import itertools
import sys
from collections.abc import Iterable, Sequence

from ..model.formats import SAVE_FORMATS, FormatError, Problem, save_records
from ..model.formats.save import save_format_for
from ..model.inert_text import one_line, plural
from ..model.store.record import LogRecord
from ..sources.files import LogFile, latest_run, load_records, open_logs
from ..sources.files.journal_file import journal_file
from .arguments import add_last_argument, add_log_format_argument
from .location_options import add_location_arguments, apply_location_arguments
from .warehouse_windows import Windows, merged

CLEAN, PROBLEMS, NOTHING_WRITTEN = 0, 1, 2
#: Longest problem text printed (a file's own text may be quoted in it).
_PROBLEM_LIMIT = 2_000


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="console-tui convert",
        description=(
            "Read log files and recordings (any format console-tui opens), merge them by time "
            "and save them as rqt_console CSV or JSON Lines. Problems go to stderr."
        ),
        epilog=(
            "Exit status: 0 every input read cleanly; 1 written, with problems (listed on stderr); "
            "2 nothing written (bad usage, nothing readable, or the output cannot be written)."
        ),
    )
    parser.add_argument(
        "inputs",
        nargs="*",
        metavar="IN",
        help="log files, recordings, or folders of them (a ROS run folder, the whole log directory), or a "
        "log warehouse: clickhouse://host:8123/db, clickhouses://..., chdb:///directory (?table=NAME)",
    )
    add_last_argument(parser)
    parser.add_argument("-o", "--output", required=True, metavar="OUT", help="file to write ('-': standard output)")
    parser.add_argument(
        "--format",
        choices=sorted(SAVE_FORMATS),
        help="rqt: rqt_console (ROS 2); rqt1: rqt_console (ROS 1); jsonl: JSON Lines, lossless "
        "(default: jsonl for .jsonl/.ndjson/.json, else rqt)",
    )
    add_log_format_argument(parser)
    add_location_arguments(parser, window_rows=True)
    return parser


def say(text: str) -> None:
    """One line to stderr, made inert: names and texts from files never reach the terminal raw."""
    print(f"console-tui convert: {one_line(text, _PROBLEM_LIMIT)}", file=sys.stderr)


def main(argv: Sequence[str]) -> int:
    """Convert as the arguments say; returns the exit status (see the module's text)."""
    parser = build_parser()
    args = parser.parse_args(list(argv))
    apply_location_arguments(parser, args, follow=False, name="inputs")  # journal: read to its end, as a file
    inputs = list(args.files)
    named = list(args.inputs)  # as given: files, journal:, warehouses
    if args.last:
        try:
            latest = [str(path) for path in latest_run()]
        except FormatError as error:
            say(str(error))
            return NOTHING_WRITTEN
        inputs += latest
        named += latest
    if not inputs and not args.journals and not args.warehouses:
        parser.error("give the files to convert, or --last")
    opened = open_logs(inputs, log_format=args.log_format)
    opened.files += [journal_file(query, log_format=args.log_format or "") for query in args.journals]
    windows = Windows(args, None, say, max_rows=args.max_messages)
    files, failures = opened.files, opened.failures
    save_format = args.format or ("rqt" if args.output == "-" else save_format_for(args.output))
    try:
        records = (record for batch in merged([load_records(files), *windows.streams()]) for record in batch)
        first = next(records, None)  # nothing is written before there is something to write
        if first is None:
            _report(failures, files)
            say(f"nothing written: no record could be read from {_inputs(named)}")
            return NOTHING_WRITTEN
        everything = itertools.chain((first,), records)
        if args.output == "-":
            count = _write_stdout(everything, save_format)
        else:
            count = save_records(everything, args.output, save_format)
    except OSError as error:
        _report(failures, files)
        say(f"cannot write {args.output}: {error.strerror or error}")
        return NOTHING_WRITTEN
    finally:
        windows.close()
        for file in files:
            file.close()
    found = _report(failures, files) + windows.failed
    for file in files:
        for note in file.notes():
            say(f"{file.source}: note: {note}")
    if opened.skipped:
        shown = ", ".join(path.name for path in opened.skipped[:5]) + (", ..." if len(opened.skipped) > 5 else "")
        say(
            f"note: {plural(len(opened.skipped), 'file')} in the folders were not read (empty, or not logs by name): {shown}"
        )
    if args.output != "-":
        read_from = plural(len(files), "file") + (
            f" and {plural(len(args.warehouses), 'log warehouse')}" if args.warehouses else ""
        )
        say(f"{plural(count, 'record')} from {read_from} written to {args.output} ({save_format})")
    return PROBLEMS if found else CLEAN


def _inputs(names: Sequence[str]) -> str:
    return names[0] if len(names) == 1 else f"any of the {len(names)} inputs"


def _report(failures: list[Problem], files: list[LogFile]) -> int:
    """Every problem on stderr; returns how many there were."""
    count = 0
    for problem in failures:
        say(str(problem))
        count += 1
    for file in files:
        for problem in file.problems:
            say(str(problem))
            count += 1
        if file.problems.omitted:
            say(f"{file.source}: {plural(file.problems.omitted, 'more problem')}")
            count += file.problems.omitted
    return count


def _write_stdout(records: Iterable[LogRecord], save_format: str) -> int:
    count = 0
    stream = sys.stdout.buffer
    for count in SAVE_FORMATS[save_format]().write(records, stream):  # noqa: B007 - the last count is the total
        pass
    stream.flush()
    return count
