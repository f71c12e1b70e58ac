"""What a positional argument names: a file or folder (as always), or a source of another kind.

The one dispatch of the command line's positional arguments (the app, ``tail``, ``convert``,
``serve``'s consoles): ``location_kind(text)`` asks each row of ``KINDS`` in turn; the first
that recognises the text names its kind, and anything no row takes is a file (or folder),
read as before (a ``*.journal`` file or a journal directory among them: the files' opener
knows those). A new kind of source adds one row: a name and a function that recognises its
text. ``split_locations`` sorts a command line's arguments by kind, keeping their order
within each; what each kind then means is its own module's (``warehouse/address.py``,
``journal/journal_location.py``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from ..warehouse.address import is_warehouse
from .journal.journal_location import follows_journal

FILE = "file"
#: ``clickhouse://``, ``clickhouses://``, ``chdb://``: a log warehouse's table, read back.
WAREHOUSE = "warehouse"
#: ``journal:``, ``journal:UNIT``, ``journal:PATH``: the systemd journal, followed.
JOURNAL = "journal"

#: (kind, recognises its text): the first that says yes names the argument's kind.
KINDS: tuple[tuple[str, Callable[[str], bool]], ...] = (
    (WAREHOUSE, is_warehouse),
    (JOURNAL, follows_journal),
)


def location_kind(text: str) -> str:
    """The kind of source a positional argument names (``FILE`` when no row takes it)."""
    for kind, recognises in KINDS:
        if recognises(text):
            return kind
    return FILE


def split_locations(arguments: Sequence[str]) -> dict[str, list[str]]:
    """The arguments by kind, in their order (every kind present, maybe empty)."""
    found: dict[str, list[str]] = {FILE: [], **{kind: [] for kind, _ in KINDS}}
    for text in arguments:
        found[location_kind(text)].append(text)
    return found
