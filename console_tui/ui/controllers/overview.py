"""The overview: the timeline strip, storms collapsed in the table, the summary.

The model does the counting (``Timeline``, ``StormRows``; the summary reads the app's
``NodeStats``, which the node panel shares), kept up to date as records arrive (``follow``,
inside the table's ``keeping_position``) and, after a rule change, caught up in the background
in slices with the event loop free between them, as the rules are.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable, Sequence
from typing import ClassVar

from ...model.overview.node_stats import NodeStats
from ...model.overview.shown_follower import sync_together
from ...model.overview.storms import StormRows
from ...model.overview.timeline import Timeline
from ...model.rules.ruleset import RuleSet
from ...sources.status import SourceStatus
from ..command_table import Command
from ..focus import focus_now
from ..slicing import pause_between_slices
from ..widgets.timeline_strip import TimelineStrip
from .context import ConsoleContext

#: Taking in what arrived, each tick: at most this long (the rest in the background).
FOLLOW_BUDGET_S = 0.010
#: Catching up after a rule change (or over a history at start): slices of this long, the
#: event loop free between them. A slice adds to the frame drawn in the same turn of the
#: loop, as the search's do (docs/decisions/0016-background-work-in-slices.md).
CATCH_UP_BUDGET_S = 0.010
CATCH_UP_PAUSE_S = 0.001
#: While the view is still filtering the oldest records, the catch-up looks again this often.
REFILTER_POLL_S = 0.01
#: The strip is redrawn at most this often while records arrive.
STRIP_PERIOD_S = 0.25


class OverviewController:
    """The timeline, the storms and the summary."""

    def __init__(
        self,
        context: ConsoleContext,
        timeline: Timeline,
        storms: StormRows,
        strip: TimelineStrip,
        node_stats: NodeStats,
        *,
        sources: Callable[[], Sequence[SourceStatus]],
    ) -> None:
        c = context
        self._host, self._store, self._view, self._table = c.host, c.store, c.view, c.table
        self._clock, self._utc, self._changed = c.clock, c.utc, c.changed
        #: Storm rows are marked with their counts.
        self._decorations = c.table.decorations
        self._timeline = timeline
        self._storms = storms
        self._strip = strip
        self._node_stats = node_stats
        #: The live sources' states: the summary says what each reads and lost.
        self._sources = sources
        self._catching_up = False
        self._strip_at = 0.0
        #: The table followed the tail when the strip was last updated.
        self._strip_following = False
        #: The store's end when the strip was last updated.
        self._strip_end = -1
        #: The summary screen is open (its key does nothing meanwhile).
        self.summary_open = False
        announce = context.announce
        announce.placing.subscribe(self.follow)
        announce.tick.subscribe(self.show)
        announce.rules_changed.subscribe(self._rules_changed)
        announce.cleared.subscribe(self._cleared)

    def start(self) -> None:
        """Once the table is there: storm rows get their marks, and what is in the store is taken in."""
        self._decorations.show_badges(self._storms.badge)
        self.follow()

    # -- keeping up ---------------------------------------------------------------------------------

    def follow(self) -> None:
        """Take in what arrived (call inside the table's ``keeping_position``); what is left
        (after a rule change: everything) is caught up in the background."""
        caught_up = True
        for follower in (self._storms, self._timeline):
            if follower.rebuilding or not follower.sync(FOLLOW_BUDGET_S):
                caught_up = False
        if not caught_up:
            self._catch_up()

    def _catch_up(self) -> None:
        if not self._catching_up:
            self._catching_up = True
            self._host.run_worker(
                self._catch_up_in_background(), name="_catch_up_in_background", group="overview", exclusive=True
            )

    async def _catch_up_in_background(self) -> None:
        try:
            while self._storms.behind or self._timeline.behind:
                if self._view.filtered and self._view.refiltering:
                    await asyncio.sleep(REFILTER_POLL_S)  # the view decides the oldest rows first
                    continue
                with self._table.keeping_position(cursor_line=True):
                    sync_together((self._storms, self._timeline), CATCH_UP_BUDGET_S)  # one pass for both
                if not (self._storms.behind or self._timeline.behind):
                    break  # the strip and the status line say so in this same turn of the loop
                await pause_between_slices(CATCH_UP_PAUSE_S)
            self._timeline.sync()  # done: the counts from before the change go
        finally:
            self._catching_up = False
        self.show(now=True)
        self._changed()  # the storms counted

    def show(self, *, force: bool = False, now: bool = False) -> None:
        """The strip follows the counts and the table's place a few times a second, or now
        with ``force`` -- except while the table follows the tail and records arrive: then
        the table says it changed every tick, and the strip waits for its time. With ``now``
        (the rules changed, or the counts after a change are done), now in any case."""
        strip = self._strip
        if not strip.shown:
            return
        clock = self._clock()
        table, end = self._table, self._store.end_seq
        following = table.following and table.paused_end is None
        due = now or clock - self._strip_at >= STRIP_PERIOD_S or strip.has_focus
        if not due:
            at_the_tail = following and self._strip_following and end != self._strip_end and strip.position is not None
            if not force or at_the_tail:
                return
        self._strip_at, self._strip_following, self._strip_end = clock, following, end
        strip.update_from_model(self._table_span(), self._view.filtered)

    def _table_span(self) -> tuple[int, int] | None:
        """Stamps of the first and last rows on the table's screen."""
        table = self._table
        rows = table.row_count
        if not rows:
            return None
        top = min(int(table.scroll_y), rows - 1)
        bottom = min(top + max(table.size.height - 2, 0), rows - 1)
        store, seq_at = self._store, table.view.seq_at
        first, last = seq_at(top), seq_at(bottom)
        if first not in store or last not in store:
            return None
        return store.stamp_of(first), store.stamp_of(last)

    def set_enabled(self, enabled: bool) -> None:
        """The timeline and the storms on, or off altogether (nothing counted: the screen
        benchmark's run without them)."""
        self._timeline.set_enabled(enabled)
        self._storms.set_enabled(enabled)
        self._decorations.show_badges(self._storms.badge if enabled else None)
        self._strip.set_class(not enabled, "-hidden")
        if enabled:
            self._catch_up()

    def _rules_changed(self, _rules: RuleSet) -> None:
        with self._table.keeping_position(cursor_line=True):
            self.follow()  # the storms and the timeline count again under these rules
        self.show(now=True)  # counting again, or (the same rows shown) counted already

    def _cleared(self) -> None:
        self._node_stats.clear()
        self._storms.restart()
        self._timeline.restart()
        self.show(force=True)

    # -- the timeline -------------------------------------------------------------------------------

    def toggle_timeline(self) -> None:
        strip = self._strip
        if strip.shown:
            if strip.has_focus:
                focus_now(self._table)
            strip.add_class("-hidden")
        else:
            strip.remove_class("-hidden")
            self.show(force=True)

    def pick_time(self) -> None:
        """Pick a column of the timeline with the keys (showing it if hidden)."""
        strip = self._strip
        if strip.has_focus:
            focus_now(self._table)
            return
        if not strip.shown:
            strip.remove_class("-hidden")
        self.show(force=True)
        focus_now(strip)

    def show_seq(self, seq: int) -> bool:
        """Put the table's cursor on the row showing ``seq`` (its storm's row when it is a
        collapsed repeat; the next row when the rules hide it), a third down the screen."""
        table = self._table
        rows = table.row_count
        if not rows:
            return False
        row = min(self._storms.row_showing(seq), rows - 1)
        height = max(table.size.height - 1, 1)
        table.following = False
        table.set_scroll(None, max(min(row - height // 3, rows - height), 0))
        table.move_cursor(row)
        self.show(force=True)
        return True

    # -- storms -------------------------------------------------------------------------------------

    def toggle_storm(self) -> None:
        """Expand the selected row's storm, or collapse it again."""
        seq = self._table.cursor_seq
        storm = self._storms.storm_of(seq) if seq is not None else None
        if storm is None:
            self._host.notify("This row is no storm: no repeats of its message follow it.", timeout=3)
            return
        with self._table.keeping_position():
            if storm.expanded:
                self._storms.collapse(storm)
            else:
                self._storms.expand(storm)
        if self._table.cursor_seq != storm.head:
            self.show_seq(storm.head)
        self._decorations.changed()  # the storms' rows and counts

    def toggle_storms(self) -> None:
        """Storms collapsed, or every message a row."""
        storms = self._storms
        with self._table.keeping_position():
            storms.set_enabled(not storms.enabled)
            if storms.enabled:
                storms.sync(FOLLOW_BUDGET_S)
        self._decorations.show_badges(storms.badge if storms.enabled else None)
        if storms.behind:
            self._catch_up()
        self._host.notify(
            "Storms collapsed: repeats show as one row (×N)"
            if storms.enabled
            else "Storms not collapsed: every message is a row",
            timeout=3,
        )
        self._changed()

    def toggle_mask_digits(self) -> None:
        storms = self._storms
        with self._table.keeping_position():
            storms.set_mask_digits(not storms.mask_digits)
            storms.sync(FOLLOW_BUDGET_S)
        self._decorations.changed()  # the storms' rows and counts
        if storms.behind:
            self._catch_up()
        self._host.notify(
            "Storms: digits count as the same" if storms.mask_digits else "Storms: digits must match too", timeout=3
        )

    def note(self) -> str:
        """What the status line says of the storms: ``12 storms`` (or that they are off)."""
        storms = self._storms
        if not storms.enabled:
            return "storms off"
        number = storms.storm_count
        return f"{number:,} storm{'s' if number != 1 else ''}" if number else ""

    # -- the summary --------------------------------------------------------------------------------

    def summary(self) -> None:
        """The summary of the run; the message chosen there is shown in the table. The nodes'
        counts are brought up to date first, in slices when many messages came since (the
        node panel closed, nobody counted them)."""
        if self._node_stats.sync(CATCH_UP_BUDGET_S):
            self._open_summary()
        else:
            self._host.run_worker(self._summary_when_counted(), name="summary", group="summary", exclusive=True)

    async def _summary_when_counted(self) -> None:
        while not self._node_stats.sync(CATCH_UP_BUDGET_S):
            await pause_between_slices(CATCH_UP_PAUSE_S)
        self._open_summary()

    def _open_summary(self) -> None:
        def chosen(seq: int | None) -> None:
            self.summary_open = False
            if seq is None:
                return
            if seq not in self._store:
                self._host.notify("That message is no longer kept.", timeout=4)
            elif not self._view_shows(seq):
                self._host.notify("The rules hide that message (r shows them).", timeout=5)
            else:
                self.show_seq(seq)

        from ..screens.summary import SummaryScreen  # loaded when first opened

        sources = list(self._sources())
        self.summary_open = True
        self._host.push_screen(
            SummaryScreen(self._store, self._node_stats, len(self._view), utc=self._utc, sources=sources), chosen
        )

    def _view_shows(self, seq: int) -> bool:
        view = self._view
        if not view.filtered:
            return True
        row = view.row_of(seq)
        return row < len(view) and view.seq_at(row) == seq

    COMMANDS: ClassVar[tuple[Command[OverviewController], ...]] = (
        Command(
            "overview.timeline",
            pick_time,
            "T",
            "Timeline: pick a time to show",
            title="Timeline: pick a time",
            about="The rate by severity over the whole history; Enter shows a time",
        ),
        Command(
            "overview.toggle_timeline",
            toggle_timeline,
            "ctrl+t",
            "Show / hide the timeline",
            about="The strip of the message rate above the table",
        ),
        Command(
            "overview.storm",
            toggle_storm,
            "z",
            "Expand / collapse the row's storm",
            title="Expand / collapse this storm",
            about="The repeats of the selected row's message, each a row",
        ),
        Command(
            "overview.storms",
            toggle_storms,
            "Z",
            "Storms collapsed on / off",
            about="A node's repeats of one message as one row (×N), or every message a row",
        ),
        Command(
            "overview.mask_digits",
            toggle_mask_digits,
            title="Storms: digits count as the same",
            about="'took 12 ms' repeats 'took 9 ms' (on / off)",
        ),
        Command(
            "overview.summary",
            summary,
            "S",
            "Summary of the run",
            applies=lambda o: not o.summary_open,
            title="Summary",
            about="Counts per severity and node, the busiest nodes, the first ERROR and FATAL",
        ),
    )
