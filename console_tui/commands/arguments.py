"""Command-line arguments that several ``console-tui`` commands share."""

from __future__ import annotations

import argparse


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


def positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1")
    return value
