"""How the log table marks each row beyond its record, from one provider that each concern
contributes its part to: the rules highlight or dim rows, the overview marks a storm's row with
its count, the search marks where it matches, the marks and the search put a glyph in the
gutter. The table reads them as it draws a row (``LogTable`` keys the rows it keeps drawn on
what they say), and draws every row again when a contribution, or its answers, changed.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

from ...model.overview.storms import StormBadge

#: How a row is marked by the rules: None (plain), "highlight" or "dim".
Decoration = str | None
#: Where a search matches in a message as shown: (start, end) character spans.
Spans = list[tuple[int, int]]


class RowLook(NamedTuple):
    """Everything a row is drawn from beside its record (the rows kept drawn are keyed on it)."""

    cursor: bool
    selected: bool
    decoration: Decoration
    badge: StormBadge | None
    #: The gutter's glyph ("" for none), or None: no gutter.
    gutter: str | None
    #: The stamp a relative Time cell counts from, or None.
    relative: int | None


class RowDecorations:
    """The contributions, each None until someone contributes it."""

    def __init__(self) -> None:
        #: The rules: seq -> decoration.
        self.highlights: Callable[[int], Decoration] | None = None
        #: The overview: seq -> its row's storm badge (``×N until ...``), or None.
        self.badges: Callable[[int], StormBadge | None] | None = None
        #: The search: (seq, message as shown) -> the spans to mark in it.
        self.matches: Callable[[int, str], Spans] | None = None
        #: The marks and the search: seq -> one character for the gutter ("" for none).
        self.gutter: Callable[[int], str] | None = None
        #: Told when the rows look different (the table draws them again).
        self._listeners: list[Callable[[], None]] = []

    def subscribe(self, listener: Callable[[], None]) -> None:
        self._listeners.append(listener)

    def changed(self) -> None:
        """A contribution's answers changed (the storms were expanded, the rules or the
        marks changed): every row is drawn again."""
        for listener in self._listeners:
            listener()

    def show_highlights(self, highlights: Callable[[int], Decoration] | None) -> None:
        self.highlights = highlights
        self.changed()

    def show_badges(self, badges: Callable[[int], StormBadge | None] | None) -> None:
        self.badges = badges
        self.changed()

    def show_matches(self, matches: Callable[[int, str], Spans] | None, gutter: Callable[[int], str] | None) -> None:
        self.matches, self.gutter = matches, gutter
        self.changed()

    def badge_of(self, seq: int) -> StormBadge | None:
        return self.badges(seq) if self.badges is not None else None

    def look(self, seq: int, cursor: bool, selected: bool, relative: int | None) -> RowLook:
        """How the row of ``seq`` is drawn."""
        highlights, badges, gutter = self.highlights, self.badges, self.gutter
        return RowLook(
            cursor,
            selected,
            highlights(seq) if highlights is not None else None,
            badges(seq) if badges is not None else None,
            gutter(seq) if gutter is not None else None,
            relative,
        )
