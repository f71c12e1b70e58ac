"""Which command-line arguments name the systemd journal, and what they ask of it.

- ``journal:`` this machine's journal; ``journal:UNIT`` (``journal:nav.service``) its entries
  of that unit (``--unit NAME`` adds units, repeatable); ``journal:PATH`` a journal file or a
  directory of them (a name with a ``/``: unit names have none), such as
  ``systemd-journal-remote`` writes for a fleet. The app and ``tail`` follow these live
  (``--since`` for the history before); ``convert`` reads them to their end.
- a ``*.journal`` file or a journal directory given as a path is a file among the others: read
  once, merged by time (``sources/files/journal_file.py``; ``tail -f`` follows it).

``follows_journal(text)`` is the journal's row in the one dispatch of positional arguments
(``sources/locations.py``); ``journal_location(text)`` says what a ``journal:`` argument, a
journal file or a journal directory asks for (None: none of those, a file as ever).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from .journalctl import JournalQuery

PREFIX = "journal:"
#: A journal file starts with these bytes (systemd's ``journal-def.h``, the header's signature).
JOURNAL_MAGIC = b"LPKSHHRH"
#: A machine's folder in a journal directory (``/var/log/journal/<machine-id>/``).
_MACHINE_ID = re.compile(r"[0-9a-f]{32}\Z")
#: Journal files by name: active ones, and those journald set aside as damaged (``~``).
_JOURNAL_NAME = re.compile(r".+\.journal~?\Z")


@dataclass(frozen=True)
class JournalLocation:
    """A journal an argument names: ``live`` (``journal:...``, a query to follow) or not (a
    journal file or directory given as a path: a file to read)."""

    live: bool
    units: tuple[str, ...] = ()
    #: A journal file or directory, or "" for this machine's journal.
    path: str = ""

    def query(self, *, since: str = "", units: Sequence[str] = (), follow: bool = False) -> JournalQuery:
        """What to ask journalctl; ``units`` (``--unit``) besides the location's own."""
        path = Path(self.path) if self.path else None
        files = (self.path,) if path is not None and not path.is_dir() else ()
        directory = self.path if path is not None and path.is_dir() else ""
        return JournalQuery(files=files, directory=directory, units=(*self.units, *units), since=since, follow=follow)

    @property
    def name(self) -> str:
        """As a person wrote it: ``journal:nav.service``."""
        if not self.live:
            return self.path
        return PREFIX + (self.path or ",".join(self.units))


def journal_location(text: str) -> JournalLocation | None:
    """The journal ``text`` names, or None (a file or folder like any other)."""
    if text.startswith(PREFIX):
        rest = text[len(PREFIX) :]
        if "/" in rest:
            return JournalLocation(live=True, path=rest)
        return JournalLocation(live=True, units=tuple(unit for unit in rest.split(",") if unit))
    path = Path(text)
    if is_journal_folder(path) or is_journal_file(path):
        return JournalLocation(live=False, path=text)
    return None


def follows_journal(text: str) -> bool:
    """Whether an argument is a journal to follow (``journal:...``): its kind in the one
    dispatch of positional arguments (``sources/locations.py``)."""
    return text.startswith(PREFIX)


def local_units(locations: Sequence[JournalLocation], units: Sequence[str]) -> list[JournalLocation]:
    """The locations as journal sources to start: this machine's journal once (the units of
    every ``journal:UNIT`` and ``--unit`` together; all of it when one says ``journal:``
    without units and no ``--unit`` is given), each journal path on its own."""
    paths = [location for location in locations if location.path]
    local = [location for location in locations if not location.path]
    if not local and not units:
        return paths
    named = [unit for location in local for unit in location.units] + list(units)
    everything = any(not location.units for location in local) and not units
    return [JournalLocation(live=True, units=() if everything else tuple(dict.fromkeys(named))), *paths]


def is_journal_file(path: Path) -> bool:
    """A journal file: named ``*.journal`` (or ``*.journal~``), or starting like one."""
    try:
        if not path.is_file():
            return False
        if _JOURNAL_NAME.match(path.name):
            return True
        with open(path, "rb") as stream:
            return stream.read(len(JOURNAL_MAGIC)) == JOURNAL_MAGIC
    except OSError:
        return False


def is_journal_folder(path: Path) -> bool:
    """A journal directory: journal files in it, or in its machines' folders (as
    ``/var/log/journal`` and what ``systemd-journal-remote`` writes are laid out)."""
    try:
        if not path.is_dir():
            return False
        for entry in path.iterdir():
            if _JOURNAL_NAME.match(entry.name) and entry.is_file():
                return True
            machine = _MACHINE_ID.match(entry.name) and entry.is_dir()
            if machine and any(_JOURNAL_NAME.match(inner.name) for inner in entry.iterdir()):
                return True
    except OSError:
        return False
    return False
