"""The app's overview: the timeline strip, storms collapsed in the table, the summary.

A part of ``ConsoleApp`` (it mixes this in). The model does the counting (``Timeline``,
``StormRows``; the summary reads the app's ``NodeStats``, which the node panel shares), kept
up to date as records arrive (``follow_overview``,
inside the table's ``keeping_position``) and, after a rule change, caught up in the
background in slices with the event loop free between them, as the rules are.
"""

from __future__ import annotations

import asyncio
from typing import TYPE_CHECKING

from textual import work

from ..model.node_stats import NodeStats
from ..model.shown_follower import sync_together
from ..model.store import LogStore
from ..model.storms import StormRows
from ..model.timeline import Timeline
from ..model.view import LogView
from .app_part import AppPart
from .focus import focus_now
from .screens.summary import SummaryScreen
from .slicing import pause_between_slices
from .widgets.timeline_strip import TimelineStrip

if TYPE_CHECKING:
    from .intake_actions import Source

#: Taking in what arrived, each tick: at most this long (the rest in the background).
FOLLOW_BUDGET_S = 0.010
#: Catching up after a rule change (or over a history at start): slices of this long, the
#: event loop free between them. A slice adds to the frame drawn in the same turn of the
#: loop, as the search's do (docs/architecture.md, "Background work in slices").
CATCH_UP_BUDGET_S = 0.010
CATCH_UP_PAUSE_S = 0.001
#: While the view is still filtering the oldest records, the catch-up looks again this often.
REFILTER_POLL_S = 0.01
#: The strip is redrawn at most this often while records arrive.
STRIP_PERIOD_S = 0.25


class OverviewActions(AppPart):
    """The timeline, the storms and the summary, and their keys."""

    timeline: Timeline
    storms: StormRows
    node_stats: NodeStats
    timeline_strip: TimelineStrip
    #: The live sources (``IntakeActions``): the summary says what each reads and lost.
    sources: list[Source]
    _catching_up = False
    _strip_at = 0.0
    #: The table followed the tail when the strip was last updated.
    _strip_following = False
    #: The store's end when the strip was last updated.
    _strip_end = -1

    def make_overview(self, store: LogStore, view: LogView, utc: bool) -> StormRows:
        """The overview's model and strip; returns the rows the table shows."""
        self.timeline = Timeline(store, view)
        self.storms = StormRows(store, view)
        self.timeline_strip = TimelineStrip(self.timeline, utc=utc, id="timeline")
        return self.storms

    def start_overview(self) -> None:
        """Once the table is there: storm rows get their marks, and what is in the store is taken in."""
        self.table.badge_of = self.storms.badge
        self.follow_overview()

    # -- keeping up ---------------------------------------------------------------------------------

    def follow_overview(self) -> None:
        """Take in what arrived (call inside the table's ``keeping_position``); what is left
        (after a rule change: everything) is caught up in the background."""
        caught_up = True
        for follower in (self.storms, self.timeline):
            if follower.rebuilding or not follower.sync(FOLLOW_BUDGET_S):
                caught_up = False
        if not caught_up:
            self._catch_up()

    def _catch_up(self) -> None:
        if not self._catching_up:
            self._catching_up = True
            self._catch_up_in_background()

    @work(exclusive=True, group="overview")
    async def _catch_up_in_background(self) -> None:
        try:
            while self.storms.behind or self.timeline.behind:
                if self.view.filtered and self.view.refiltering:
                    await asyncio.sleep(REFILTER_POLL_S)  # the view decides the oldest rows first
                    continue
                with self.table.keeping_position(cursor_line=True):
                    sync_together((self.storms, self.timeline), CATCH_UP_BUDGET_S)  # one pass for both
                if not (self.storms.behind or self.timeline.behind):
                    break  # the strip and the status line say so in this same turn of the loop
                await pause_between_slices(CATCH_UP_PAUSE_S)
            self.timeline.sync()  # done: the counts from before the change go
        finally:
            self._catching_up = False
        self.show_overview(now=True)
        self.update_status()  # the storms counted

    def show_overview(self, *, force: bool = False, now: bool = False) -> None:
        """The strip follows the counts and the table's place a few times a second, or now
        with ``force`` -- except while the table follows the tail and records arrive: then
        the table says it changed every tick, and the strip waits for its time. With ``now``
        (the rules changed, or the counts after a change are done), now in any case."""
        strip = self.timeline_strip
        if not strip.shown:
            return
        clock = self.clock()
        table, end = self.table, self.store.end_seq
        following = table.following and table.paused_end is None
        due = now or clock - self._strip_at >= STRIP_PERIOD_S or strip.has_focus
        if not due:
            at_the_tail = following and self._strip_following and end != self._strip_end and strip.position is not None
            if not force or at_the_tail:
                return
        self._strip_at, self._strip_following, self._strip_end = clock, following, end
        strip.update_from_model(self._table_span(), self.view.filtered)

    def _table_span(self) -> tuple[int, int] | None:
        """Stamps of the first and last rows on the table's screen."""
        table = self.table
        rows = table.row_count
        if not rows:
            return None
        top = min(int(table.scroll_y), rows - 1)
        bottom = min(top + max(table.size.height - 2, 0), rows - 1)
        store, seq_at = self.store, table.view.seq_at
        first, last = seq_at(top), seq_at(bottom)
        if first not in store or last not in store:
            return None
        return store.stamp_of(first), store.stamp_of(last)

    def set_overview(self, enabled: bool) -> None:
        """The timeline and the storms on, or off altogether (nothing counted: the screen
        benchmark's run without them)."""
        self.timeline.set_enabled(enabled)
        self.storms.set_enabled(enabled)
        self.table.badge_of = self.storms.badge if enabled else None
        self.timeline_strip.set_class(not enabled, "-hidden")
        self.table.restyle()
        if enabled:
            self._catch_up()

    def clear_overview(self) -> None:
        """After the store was cleared."""
        self.storms.restart()
        self.timeline.restart()
        self.show_overview(force=True)

    # -- the timeline -------------------------------------------------------------------------------

    def action_toggle_timeline(self) -> None:
        strip = self.timeline_strip
        if strip.shown:
            if strip.has_focus:
                focus_now(self.table)
            strip.add_class("-hidden")
        else:
            strip.remove_class("-hidden")
            self.show_overview(force=True)

    def action_timeline(self) -> None:
        """Pick a column of the timeline with the keys (showing it if hidden)."""
        strip = self.timeline_strip
        if strip.has_focus:
            focus_now(self.table)
            return
        if not strip.shown:
            strip.remove_class("-hidden")
        self.show_overview(force=True)
        focus_now(strip)

    def on_timeline_strip_jump(self, message: TimelineStrip.Jump) -> None:
        self.show_seq(message.seq)

    def on_timeline_strip_leave(self, _message: TimelineStrip.Leave) -> None:
        focus_now(self.table)

    def show_seq(self, seq: int) -> bool:
        """Put the table's cursor on the row showing ``seq`` (its storm's row when it is a
        collapsed repeat; the next row when the rules hide it), a third down the screen."""
        table = self.table
        rows = table.row_count
        if not rows:
            return False
        row = min(self.storms.row_showing(seq), rows - 1)
        height = max(table.size.height - 1, 1)
        table.following = False
        table.set_scroll(None, max(min(row - height // 3, rows - height), 0))
        table.move_cursor(row)
        self.show_overview(force=True)
        return True

    # -- storms -------------------------------------------------------------------------------------

    def action_toggle_storm(self) -> None:
        """Expand the selected row's storm, or collapse it again."""
        seq = self.table.cursor_seq
        storm = self.storms.storm_of(seq) if seq is not None else None
        if storm is None:
            self.notify("This row is no storm: no repeats of its message follow it.", timeout=3)
            return
        with self.table.keeping_position():
            if storm.expanded:
                self.storms.collapse(storm)
            else:
                self.storms.expand(storm)
        if self.table.cursor_seq != storm.head:
            self.show_seq(storm.head)
        self.table.restyle()

    def action_toggle_storms(self) -> None:
        """Storms collapsed, or every message a row."""
        storms = self.storms
        with self.table.keeping_position():
            storms.set_enabled(not storms.enabled)
            if storms.enabled:
                storms.sync(FOLLOW_BUDGET_S)
        self.table.badge_of = storms.badge if storms.enabled else None
        self.table.restyle()
        if storms.behind:
            self._catch_up()
        self.notify(
            "Storms collapsed: repeats show as one row (×N)"
            if storms.enabled
            else "Storms not collapsed: every message is a row",
            timeout=3,
        )
        self.update_status()

    def action_toggle_mask_digits(self) -> None:
        storms = self.storms
        with self.table.keeping_position():
            storms.set_mask_digits(not storms.mask_digits)
            storms.sync(FOLLOW_BUDGET_S)
        self.table.restyle()
        if storms.behind:
            self._catch_up()
        self.notify(
            "Storms: digits count as the same" if storms.mask_digits else "Storms: digits must match too", timeout=3
        )

    def storms_note(self) -> str:
        """What the status line says of the storms: ``12 storms`` (or that they are off)."""
        storms = self.storms
        if not storms.enabled:
            return "storms off"
        number = storms.storm_count
        return f"{number:,} storm{'s' if number != 1 else ''}" if number else ""

    # -- the summary --------------------------------------------------------------------------------

    def action_summary(self) -> None:
        if isinstance(self.screen, SummaryScreen):
            return
        self.node_stats.update()

        def chosen(seq: int | None) -> None:
            if seq is None:
                return
            if seq not in self.store:
                self.notify("That message is no longer kept.", timeout=4)
            elif not self._view_shows(seq):
                self.notify("The rules hide that message (r shows them).", timeout=5)
            else:
                self.show_seq(seq)

        sources = [source.status for source in self.sources]
        self.push_screen(
            SummaryScreen(self.store, self.node_stats, len(self.view), utc=self.utc, sources=sources), chosen
        )

    def _view_shows(self, seq: int) -> bool:
        view = self.view
        if not view.filtered:
            return True
        row = view.row_of(seq)
        return row < len(view) and view.seq_at(row) == seq
