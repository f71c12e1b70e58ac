"""What a positional argument names: a file or folder (as always), or a source with a scheme.

``location_kind(text)`` asks each row of ``KINDS`` in turn; the first that recognises the text
names its kind, and anything no row takes is a file (or folder), read as before. A new kind of
source adds one row (a name and a function that recognises its text). ``split_locations``
sorts a command line's arguments by kind, keeping their order within each.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from ..warehouse.address import is_warehouse

FILE = "file"
WAREHOUSE = "warehouse"

#: (kind, recognises its text): the first that says yes names the argument's kind.
KINDS: list[tuple[str, Callable[[str], bool]]] = [
    (WAREHOUSE, is_warehouse),  # clickhouse://, clickhouses://, chdb://
]


def location_kind(text: str) -> str:
    """The kind of source a positional argument names (``FILE`` when no row takes it)."""
    for kind, recognises in KINDS:
        if recognises(text):
            return kind
    return FILE


def split_locations(arguments: Sequence[str]) -> dict[str, list[str]]:
    """The arguments by kind, in their order (``FILE`` always present)."""
    found: dict[str, list[str]] = {FILE: []}
    for text in arguments:
        found.setdefault(location_kind(text), []).append(text)
    return found
