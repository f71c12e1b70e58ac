"""Search without filtering: the search line, next / previous match, the marks on matching rows.

The search itself is the model's ``Search``: it walks the history in slices on the event loop
(the screen never waits), newer or older first as the jump asked for needs, and the status
line says "match 3 of 17".
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

from textual.worker import Worker

from ...model.inert_text import plural
from ...model.overview.search_rows import MatchRows
from ...model.overview.storms import StormRows
from ...model.rules.time_limit import MatchTimeout, time_limit
from ...model.view.search_walk import PENDING, Search, describe_search, display_pattern, parse_search
from ..command_table import NAVIGATION, Command
from ..focus import focus_now
from ..slicing import pause_between_slices
from ..widgets.log_table import Spans
from ..widgets.search_bar import SearchBar
from .announcements import TakenIn
from .context import ConsoleContext

#: Slices of the search on the event loop, and the pause between them. A slice adds to the
#: frame drawn in the same turn of the loop, so it is short enough to keep the longest stall
#: near the floor (the slices tried: docs/decisions/0016-background-work-in-slices.md).
SEARCH_BUDGET_S = 0.003
SEARCH_PAUSE_S = 0.001
#: After the table moved or its marks changed, the pause that leaves the next frame (every
#: row drawn again) a turn of the loop without a slice in it.
SEARCH_FRAME_GAP_S = 1 / 60
#: How often the status line's count moves while searching.
SEARCH_PROGRESS_PERIOD_S = 0.1
#: Finding the matches in one row as shown (a regex) may take this long at most.
ROW_MARK_LIMIT_S = 0.05
MARK_GLYPH, MATCH_GLYPH = "●", "»"


@dataclass
class _Jump:
    """A jump waiting for the search: from ``seq``, in that direction."""

    seq: int
    forward: bool
    inclusive: bool = False
    #: Nothing that way: try the other way (the first jump as you type).
    either_way: bool = False


class SearchController:
    """Search without filtering: every match marked, n / N across the whole history."""

    def __init__(self, context: ConsoleContext, search_bar: SearchBar, storms: StormRows) -> None:
        c = context
        self._host, self._store, self._view, self._table, self._marks = c.host, c.store, c.view, c.table, c.marks
        self._clock, self._changed = c.clock, c.changed
        self._search_bar = search_bar
        self._storms = storms
        #: The search in force, or None.
        self.search: Search | None = None
        self._search_rules: object = None
        self._search_origin: tuple[int | None, bool] | None = None
        self._jump: _Jump | None = None
        self._search_text = ""
        self._match_rows: tuple[tuple, MatchRows] | None = None
        self._worker: Worker[None] | None = None
        context.announce.taken_in.subscribe(self.after_records)
        context.announce.marks_changed.subscribe(self.show_marks)  # the gutter shows them

    # -- the search line ----------------------------------------------------------------------

    def open_search_line(self) -> None:
        table = self._table
        self._search_origin = (table.cursor_seq, table.following)
        self._search_bar.open(self._search_text)

    def search_line_changed(self, message: SearchBar.Changed) -> None:
        origin, following = self._search_origin or (self._table.cursor_seq, self._table.following)
        if not message.text.strip():
            self.clear_search()
            self._go_back(origin, following)
            return
        self.start_search(message.text, origin, first_jump=True, newest_first=following)

    def search_line_done(self, message: SearchBar.Done) -> None:
        if not message.keep:
            origin, following = self._search_origin or (None, False)
            self.clear_search()
            self._go_back(origin, following)
        focus_now(self._table)
        self._search_origin = None

    def _go_back(self, seq: int | None, following: bool) -> None:
        if following:
            self._table.follow()
        elif seq is not None and seq in self._store:
            self._table.jump_to_seq(seq)

    # -- searching ----------------------------------------------------------------------------

    def start_search(self, text: str, anchor: int | None = None, *, first_jump: bool, newest_first: bool) -> None:
        """Search for ``text`` from ``anchor`` (the selected row); with ``first_jump`` go to the
        match nearest it (the newest when ``newest_first``, else the next one down)."""
        match = parse_search(text)
        if anchor is None:
            anchor = self._table.cursor_seq
        start = anchor if anchor is not None else self._store.end_seq
        self._search_text = text.strip()
        self.search = Search(self._view, match, start)
        self._search_rules = self._view.rules
        self._jump = _Jump(start, forward=not newest_first, inclusive=True, either_way=True) if first_jump else None
        self.show_marks()
        self._search_on()

    def clear_search(self) -> None:
        self.search = None
        self._jump = None
        self._search_text = ""
        if self._worker is not None:
            self._worker.cancel()
        self.show_marks()
        self._changed()

    def jump_to_match(self, *, forward: bool) -> None:
        search = self._fresh_search()
        if search is None:
            self._host.notify("No search yet: f finds a text or a /regex/.", timeout=4)
            return
        seq = self._table.cursor_seq
        if seq is None:
            return
        self._jump = _Jump(seq, forward)
        if not self._try_jump():
            self._search_on()

    def _fresh_search(self) -> Search | None:
        """The search, started again from the selected row when the rules changed (which
        rows are shown changed with them)."""
        search = self.search
        if search is not None and self._view.rules is not self._search_rules:
            anchor = self._table.cursor_seq
            jump = self._jump
            self.start_search(self._search_text, anchor, first_jump=False, newest_first=False)
            self._jump = jump
            search = self.search
        return search

    def _try_jump(self) -> bool:
        """Go to the match the waiting jump asks for, if the search knows it; True when the
        jump is done (gone there, or said there is none)."""
        jump, search = self._jump, self.search
        if jump is None or search is None:
            return True
        limit = self._table.paused_end
        found = search.nearest(jump.seq, forward=jump.forward, inclusive=jump.inclusive, limit=limit)
        if jump.forward and not jump.inclusive:
            # Row to row: past the matches the cursor's row shows (a collapsed storm's repeats).
            row = self._table.cursor_row
            while found is not None and found != PENDING and self._storms.row_showing(found) <= row:
                found = search.nearest(found, forward=True, limit=limit)
        if found == PENDING:
            return False
        if found is None and jump.either_way:
            other = search.nearest(jump.seq, forward=not jump.forward, inclusive=jump.inclusive, limit=limit)
            if other == PENDING:
                return False
            found = other
        self._jump = None
        if found is not None:
            self._table.jump_to_seq(found)
        elif not jump.either_way:
            where = "below" if jump.forward else "above"
            self._host.notify(f"No match {where} for {describe_search(search.match)}", timeout=3)
        self._changed()
        return True

    def _search_on(self) -> None:
        """Keep the search walking in the background (when it has something to do)."""
        search = self.search
        busy = search is not None and (not search.complete or self._jump is not None)
        if busy and not (self._worker is not None and self._worker.is_running):
            self._worker = self._host.run_worker(
                self._search_in_background(), name="_search_in_background", group="search", exclusive=True
            )

    async def _search_in_background(self) -> None:
        shown_at = self._clock()
        marked = -1
        while True:
            search = self._fresh_search()
            if search is None:
                return
            if not self._view.refiltering:  # the rows shown are known
                jump = self._jump
                prefer = 0 if jump is None else (1 if jump.forward else -1)
                complete = search.step(SEARCH_BUDGET_S, prefer)
                if search.failed:
                    self._host.notify(
                        f"Search stopped, {search.failed}: {describe_search(search.match)}", severity="error"
                    )
                    self._jump = None
                waiting = self._jump is not None
                jumped = self._try_jump()
                redrawn = waiting and jumped  # the table moved to a match
                if self._clock() - shown_at >= SEARCH_PROGRESS_PERIOD_S or complete:
                    shown_at = self._clock()
                    found = search.count()
                    if found != marked:  # new matches may be on screen: draw their marks
                        marked = found
                        self.show_marks()
                        redrawn = True
                    self._changed()
                if complete and jumped:
                    return
                if redrawn:  # the frame that draws it goes first, in a turn of its own
                    await pause_between_slices(SEARCH_FRAME_GAP_S)
                    continue
            await pause_between_slices(SEARCH_PAUSE_S)

    def after_records(self, taken: TakenIn) -> None:
        """New records arrived: they are searched too (all again when the newest ones were
        written in another order: a late history placed by its stamp)."""
        if taken.rewritten and self.search is not None:
            self._search_rules = None
            self._fresh_search()
        if self.search is not None and not self.search.complete:
            self._search_on()

    # -- what the table and the status line show ------------------------------------------------

    def show_marks(self) -> None:
        table = self._table
        search = self.search
        matches: Callable[[int, str], Spans] | None = None
        if search is not None:
            pattern = display_pattern(search.match)
            regex = search.match.regex

            def spans(seq: int, text: str) -> Spans:
                if not search.is_match(seq):
                    return []
                try:
                    if regex:
                        with time_limit(ROW_MARK_LIMIT_S):
                            return [m.span() for m in pattern.finditer(text) if m.end() > m.start()]
                    return [m.span() for m in pattern.finditer(text) if m.end() > m.start()]
                except MatchTimeout:
                    return []

            matches = spans
        gutter = self._gutter if search is not None or len(self._marks) else None
        table.decorations.show_matches(matches, gutter)

    def _gutter(self, seq: int) -> str:
        if seq in self._marks:
            return MARK_GLYPH
        search = self.search
        return MATCH_GLYPH if search is not None and search.is_match(seq) else ""

    def search_status(self) -> str:
        """``match 3 of 17 'timeout'``, ``17 matches 'timeout'``, ``searching 'timeout': 5 found``,
        ``no match 'timeout'``, ``search stopped: ...`` (the regex took too long), or ""."""
        search = self._fresh_search()
        if search is None:
            return ""
        what = describe_search(search.match)
        if search.failed:
            return f"search stopped: {what}"
        limit = self._table.paused_end
        found = search.count(limit)
        if not search.complete:
            return f"searching {what}: {found:,} found"
        if not found:
            return f"no match {what}"
        seq = self._table.cursor_seq
        if limit is None:  # counted as rows: a collapsed storm's matches are one
            rows = self._rows_of(search)
            index = rows.index(seq) if seq is not None else None
            messages = f"in {rows.rows:,} rows, {plural(rows.messages, 'message')}" if rows.rows != found else ""
            found = rows.rows
        else:
            index = search.index(seq) if seq is not None else None
            messages = ""
        if index is not None:
            said = f"match {index:,} of {found:,} {what}"
        else:
            said = f"{plural(found, 'match', 'matches')} {what}"
        return f"{said}: {messages}" if messages else said

    def _rows_of(self, search: Search) -> MatchRows:
        """The rows holding matches (counted again when the matches or the storms changed)."""
        storms = self._storms
        key = (
            search,
            search.count(),
            storms.done_to,
            len(storms),
            storms.storm_count,
            storms.mask_digits,
            storms.enabled,
        )
        if self._match_rows is None or self._match_rows[0] != key:
            self._match_rows = (key, MatchRows(search, storms))
        return self._match_rows[1]

    COMMANDS: ClassVar[tuple[Command[SearchController], ...]] = (
        Command(
            "nav.find",
            open_search_line,
            "f,ctrl+f",
            "Find",
            footer=70,
            group=NAVIGATION,
            about="Search a text or /regex/ in the messages; the rows stay, matches are marked",
            words="search grep look",
        ),
        Command(
            "nav.next_match",
            lambda s: s.jump_to_match(forward=True),
            "n",
            "Next match",
            group=NAVIGATION,
            about="The next row the search matches, below",
        ),
        Command(
            "nav.previous_match",
            lambda s: s.jump_to_match(forward=False),
            "N",
            "Previous match",
            group=NAVIGATION,
            about="The previous row the search matches, above",
        ),
        Command(
            "console.clear_search",
            clear_search,
            "escape",
            "Clear the search",
            applies=lambda s: s.search is not None and not s._view.refiltering,
            about="No search: no marks, no counter",
            ends=True,
        ),
    )
