"""The systemd journal on the command line of the app, ``tail`` and ``convert``: the
``journal:`` arguments among the FILEs (``sources/journal/journal_location.py``), ``--unit``
and ``--since``, turned into the journal queries to read (``args.journals``)."""

from __future__ import annotations

import argparse

from ..sources.journal.journal_location import journal_arguments, local_units


def add_journal_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group(
        "the systemd journal (FILE 'journal:' is this machine's journal, 'journal:UNIT' a unit's entries, "
        "'journal:PATH' a journal file or directory; a *.journal file or a journal directory is read as a file)"
    )
    group.add_argument(
        "--unit",
        action="append",
        metavar="NAME",
        help="this unit's entries of this machine's journal (repeatable; the same as FILE journal:NAME)",
    )
    group.add_argument(
        "--since",
        metavar="TIME",
        help="the journal from this time, as journalctl takes it: '2026-12-06 10:00', 'yesterday', '-1h' "
        "(default when following this machine's journal: its last 1,000 entries)",
    )


def apply_journal_arguments(parser: argparse.ArgumentParser, args: argparse.Namespace, *, follow: bool) -> None:
    """Take the ``journal:`` arguments out of ``args.files`` into ``args.journals``, the
    queries to read (followed when ``follow``), with ``--unit`` and ``--since``."""
    locations, args.files = journal_arguments(args.files)
    units = args.unit or []
    if args.since is not None and not (locations or units):
        parser.error("--since goes with the journal: give journal:, journal:UNIT or --unit")
    args.journals = [
        location.query(since=args.since or "", follow=follow) for location in local_units(locations, units)
    ]
