"""``console-tui convert IN... -o OUT``: log files and recordings to one saved file."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from ..model.formats import SAVE_FORMATS, save_records
from ..model.formats.save import save_format_for
from ..sources.files import load_records, open_files
from .arguments import add_log_format_argument


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="console-tui convert",
        description=(
            "Read log files and recordings (any format console-tui opens), merge them by time "
            "and save them as rqt_console CSV or JSON Lines. Problems go to stderr."
        ),
    )
    parser.add_argument("inputs", nargs="+", metavar="IN", help="log files or recordings")
    parser.add_argument("-o", "--output", required=True, metavar="OUT", help="file to write ('-': standard output)")
    parser.add_argument(
        "--format",
        choices=sorted(SAVE_FORMATS),
        help="rqt: rqt_console (ROS 2); rqt1: rqt_console (ROS 1); jsonl: JSON Lines, lossless "
        "(default: jsonl for .jsonl/.ndjson/.json, else rqt)",
    )
    add_log_format_argument(parser)
    return parser


def main(argv: Sequence[str]) -> int:
    """Exit status 0 when every input was read, 1 when one could not be opened at all
    (the others are still written), 2 when the output cannot be written."""
    args = build_parser().parse_args(list(argv))
    files, failures = open_files(args.inputs, log_format=args.log_format)
    save_format = args.format or ("rqt" if args.output == "-" else save_format_for(args.output))
    records = (record for batch in load_records(files) for record in batch)
    try:
        if args.output == "-":
            count = _write_stdout(records, save_format)
        else:
            count = save_records(records, args.output, save_format)
    except OSError as error:
        print(f"console-tui convert: cannot write {args.output}: {error.strerror or error}", file=sys.stderr)
        return 2
    finally:
        for file in files:
            file.close()
    for problem in failures:
        print(f"console-tui convert: {problem}", file=sys.stderr)
    for file in files:
        for problem in file.problems:
            print(f"console-tui convert: {problem}", file=sys.stderr)
        if file.problems.omitted:
            print(f"console-tui convert: {file.source}: {file.problems.omitted} more problems", file=sys.stderr)
    if args.output != "-":
        print(f"{count} records from {len(files)} file(s) written to {args.output} ({save_format})", file=sys.stderr)
    return 1 if failures else 0


def _write_stdout(records, save_format: str) -> int:
    count = 0
    stream = sys.stdout.buffer
    for count in SAVE_FORMATS[save_format]().write(records, stream):  # noqa: B007 - the last count is the total
        pass
    stream.flush()
    return count
