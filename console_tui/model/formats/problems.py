"""What went wrong while reading a file: structured, located, and capped in number."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

DEFAULT_PROBLEM_LIMIT = 100


@dataclass(frozen=True, slots=True)
class Problem:
    """One problem in one file: where (line number or byte offset, when known) and what."""

    source: str
    what: str
    line: int | None = None
    offset: int | None = None

    @property
    def where(self) -> str:
        if self.line is not None:
            return f"line {self.line}"
        if self.offset is not None:
            return f"byte {self.offset}"
        return ""

    def __str__(self) -> str:
        where = self.where
        return f"{self.source}: {where}: {self.what}" if where else f"{self.source}: {self.what}"


class Problems:
    """The problems of one file, in the order found.

    The first ``limit`` are kept in full; later ones are only counted (``omitted``), so a
    file of garbage cannot fill memory with complaints. Written by one thread; any thread
    may read ``items`` (a list only ever appended to).
    """

    def __init__(self, source: str, limit: int = DEFAULT_PROBLEM_LIMIT) -> None:
        self.source = source
        self.limit = limit
        self.items: list[Problem] = []
        self.omitted = 0

    def add(self, what: str, *, line: int | None = None, offset: int | None = None) -> None:
        if len(self.items) >= self.limit:
            self.omitted += 1
            return
        self.items.append(Problem(self.source, what, line=line, offset=offset))

    def __len__(self) -> int:
        return len(self.items) + self.omitted

    def __iter__(self) -> Iterator[Problem]:
        return iter(list(self.items))

    def summary(self) -> str:
        """One line for a status bar: the first problem and how many more there are."""
        if not self.items:
            return ""
        rest = len(self) - 1
        return str(self.items[0]) + (f" (and {rest} more)" if rest else "")


class FormatError(Exception):
    """A file cannot be read at all: unknown format, empty, binary, unreadable.

    The message names the file and says what is wrong, ready to show to a user.
    """


class RecordError(ValueError):
    """One record of a file cannot be parsed; the reader notes it and goes on."""
