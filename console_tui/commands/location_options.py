"""The positional arguments of the app, ``tail`` and ``convert`` sorted by kind, and the options
that go with each kind: files and folders (``args.files``, read as ever), the systemd journal
(``journal:``, ``journal:UNIT``, ``journal:PATH`` with ``--unit``: ``args.journals``, the
queries to read) and log warehouses (``clickhouse://``, ``clickhouses://``, ``chdb://``:
``args.warehouses``, their addresses), with one ``--since`` for both and ``--until`` for the
warehouse's window. Which kind an argument is, is the one dispatch's
(``sources/locations.py``)."""

from __future__ import annotations

import argparse
import re

from ..model.rules.query import QueryError, parse_time
from ..model.store.log_store import DEFAULT_MAX_MESSAGES
from ..sources.journal.journal_location import journal_location, local_units
from ..sources.locations import FILE, JOURNAL, WAREHOUSE, split_locations
from ..warehouse.address import AddressError, parse_address
from .arguments import positive_int

#: An age as the query line writes one (``2h``), and as journalctl does (``-2h``): the same.
_AGE = re.compile(r"-?\d+(?:\.\d+)?[smhd]")


def add_location_arguments(parser: argparse.ArgumentParser, *, window_rows: bool = False) -> None:
    """``--unit`` (the journal) and ``--since``/``--until`` (the journal's start, a log
    warehouse's window); with ``window_rows``, ``--max-messages``: the newest rows of a
    warehouse's window read (the app's own bounds its store, and the window with it)."""
    journal = parser.add_argument_group(
        "the systemd journal (FILE 'journal:' is this machine's journal, 'journal:UNIT' a unit's entries, "
        "'journal:PATH' a journal file or directory; a *.journal file or a journal directory is read as a file)"
    )
    journal.add_argument(
        "--unit",
        action="append",
        metavar="NAME",
        help="this unit's entries of this machine's journal (repeatable; the same as FILE journal:NAME)",
    )
    window = parser.add_argument_group(
        "the window of the journal and of a log warehouse (FILE clickhouse://host:8123/db, clickhouses://, "
        "chdb:///DIR; ?table=NAME)"
    )
    window.add_argument(
        "--since",
        metavar="TIME",
        help="from this time: an age (2h, or --since=-2h), a time today (02:50), '2026-12-05 02:50' or an ISO "
        "time; the journal also takes what journalctl takes ('yesterday') (default: a warehouse's newest "
        "records, up to --max-messages; this machine's journal's last 1,000 entries when followed)",
    )
    window.add_argument(
        "--until",
        metavar="TIME",
        help="a log warehouse's window ends at this time, written as --since (default: now, and on)",
    )
    if window_rows:
        window.add_argument(
            "--max-messages",
            metavar="N",
            type=positive_int,
            default=DEFAULT_MAX_MESSAGES,
            help=f"of a log warehouse: the newest N records of the window at most (default {DEFAULT_MAX_MESSAGES:,})",
        )


def apply_location_arguments(
    parser: argparse.ArgumentParser, args: argparse.Namespace, *, follow: bool, name: str = "files"
) -> None:
    """Sort the positional arguments (``args.<name>``) by kind: files and folders left in
    ``args.files``, the journal queries to read (followed when ``follow``) in ``args.journals``,
    the warehouses' addresses in ``args.warehouses``; ``--since``/``--until`` read into
    ``args.since_ns``/``args.until_ns``. A bad address, a bad time or an option without its
    kind exits 2 saying which."""
    kinds = split_locations(getattr(args, name) or [])
    args.files = kinds[FILE]
    locations = [found for text in kinds[JOURNAL] if (found := journal_location(text)) is not None]
    units = getattr(args, "unit", None) or []
    args.warehouses = []
    for text in kinds[WAREHOUSE]:
        try:
            args.warehouses.append(parse_address(text))
        except AddressError as error:
            parser.error(str(error))
    journals = bool(locations or units)
    since, until = getattr(args, "since", None), getattr(args, "until", None)
    if since is not None and not (journals or args.warehouses):
        parser.error(
            "--since goes with the journal or a log warehouse: give journal:, journal:UNIT, --unit, "
            "clickhouse://... or chdb://..."
        )
    if until is not None and not args.warehouses:
        parser.error("--until goes with a log warehouse (clickhouse://..., chdb://...): give one")
    journal_since = _journal_time(since)
    args.journals = [location.query(since=journal_since, follow=follow) for location in local_units(locations, units)]
    args.since_ns = _window_time(parser, "since", since, args) if args.warehouses else None
    args.until_ns = _window_time(parser, "until", until, args) if args.warehouses else None
    if args.since_ns is not None and args.until_ns is not None and args.since_ns > args.until_ns:
        parser.error("--since is after --until")


def _journal_time(given: str | None) -> str:
    """``--since`` as journalctl takes it: an age written ``2h`` is ``-2h`` there; anything
    else as given (journalctl says what it does not take)."""
    text = (given or "").strip()
    return "-" + text.lstrip("-") if _AGE.fullmatch(text) else text


def _window_time(
    parser: argparse.ArgumentParser, option: str, given: str | None, args: argparse.Namespace
) -> int | None:
    """A warehouse's ``--since``/``--until`` in nanoseconds since the epoch (None: not given)."""
    if not given:
        return None
    text = given.strip()
    try:
        return parse_time(text.lstrip("-") if _AGE.fullmatch(text) else text, utc=bool(getattr(args, "utc", False)))
    except QueryError:
        parser.error(f"--{option}: not a time: {given!r} (2h, 02:50, '2026-12-05 02:50', an ISO time)")
