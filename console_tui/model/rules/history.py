"""Past queries, newest last, with up/down navigation like a shell's."""

from __future__ import annotations

import os
from pathlib import Path


class QueryHistory:
    """Up to ``limit`` distinct queries; ``previous``/``following`` walk them from a draft."""

    def __init__(self, items: list[str] | None = None, limit: int = 200) -> None:
        self.limit = limit
        self.items: list[str] = []
        for item in items or []:
            self.add(item)
        self._cursor: int | None = None  # index into items while walking
        self._draft = ""

    def add(self, query: str) -> None:
        """Remember a query that was applied (blank ones are not kept; a repeat moves to the end)."""
        query = " ".join(query.splitlines()).strip()
        self._cursor = None
        if not query:
            return
        if query in self.items:
            self.items.remove(query)
        self.items.append(query)
        del self.items[: max(len(self.items) - self.limit, 0)]

    def previous(self, draft: str) -> str | None:
        """The query before the one shown (``draft`` is what is typed now); None at the oldest."""
        if self._cursor is None:
            if not self.items:
                return None
            self._draft, self._cursor = draft, len(self.items)
        if self._cursor == 0:
            return None
        self._cursor -= 1
        return self.items[self._cursor]

    def following(self) -> str | None:
        """The query after the one shown; back at the end, the draft; None when not walking."""
        if self._cursor is None:
            return None
        self._cursor += 1
        if self._cursor >= len(self.items):
            self._cursor = None
            return self._draft
        return self.items[self._cursor]

    @classmethod
    def load(cls, path: str | os.PathLike[str], limit: int = 200) -> QueryHistory:
        """From a file of one query a line; a missing or unreadable file gives an empty history."""
        try:
            lines = Path(path).read_text(encoding="utf-8").splitlines()
        except (OSError, UnicodeDecodeError):
            lines = []
        return cls(lines, limit)

    def save(self, path: str | os.PathLike[str]) -> None:
        target = Path(path)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text("".join(item + "\n" for item in self.items), encoding="utf-8")
