"""Rules and filtering: the query line, the rules pane, quick rules, rule files, and the
rules put in force over the history in the background.
"""

from __future__ import annotations

import asyncio
import os
from typing import ClassVar

from ...model.inert_text import plural
from ...model.rules.history import QueryHistory
from ...model.rules.query import parse_query
from ...model.rules.rule import RuleError
from ...model.rules.ruleset import Entry, Role, RuleSet
from ...model.rules.rulesfile import last_rules_path, load_rules, query_history_path, save_rules
from ..command_table import Command
from ..screens.quick_rule import QuickRuleScreen
from ..screens.rule_editor import RuleEditor
from ..slicing import pause_between_slices
from ..widgets.query_bar import QueryBar
from ..widgets.rules_pane import RulesPane
from .announcements import TakenIn
from .context import ConsoleContext

#: Background filtering after a rule change: slices of this long, with the event loop free this long between them.
REFILTER_BUDGET_S = 0.015
REFILTER_PAUSE_S = 0.001
REFILTER_FIRST_PAUSE_S = 0.02
#: How often the status line's "filtering N%" moves.
REFILTER_PROGRESS_PERIOD_S = 0.1
#: Quick rules look at this many selected rows at most.
QUICK_RULE_ROWS = 10_000


class RulesController:
    """Rules in force, and every way to change them."""

    def __init__(
        self, context: ConsoleContext, query_bar: QueryBar, rules_pane: RulesPane, query_history: QueryHistory
    ) -> None:
        c = context
        self._host, self._store, self._view, self._table = c.host, c.store, c.view, c.table
        self._clock, self._utc, self._changed, self._announce = c.clock, c.utc, c.changed, c.announce
        self._query_bar = query_bar
        self._rules_pane = rules_pane
        self._query_history = query_history
        #: The rules in force; a new set replaces it whole (rule sets are values).
        self.rules = RuleSet()
        self._counts_at = 0.0
        context.announce.taken_in.subscribe(self._after_records)
        context.announce.tick.subscribe(self.follow_counts)

    def apply_rules(self, rules: RuleSet) -> None:
        """Put ``rules`` in force: the screenful around the selected row (the newest while
        following the tail) at once, the rest in the background; the selected record stays
        on its line (or the nearest shown in time)."""
        table = self._table
        around = None if table.following and table.paused_end is None else table.cursor_seq
        with table.keeping_position(cursor_line=True):
            self._view.set_rules(rules, around=around)
        self.rules_changed()

    def rules_changed(self) -> None:
        """Show the view's rules as the rules in force (the view switches off a rule too slow
        to test, and says which)."""
        table = self._table
        rules = self.rules = self._view.rules
        table.decorations.show_highlights(self._view.decoration_of if rules.highlighting else None)
        self._announce.rules_changed(rules)  # the storms and the timeline count again under them
        for rule, why in self._view.take_switched_off():
            self._host.notify(f"Rule switched off, {why}: {rule.describe()}", severity="error", timeout=15)
        if self._view.refiltering:
            self._host.run_worker(
                self._filter_in_background(), name="_filter_in_background", group="refilter", exclusive=True
            )
        self.show_counts()
        self._changed()

    def _after_records(self, _taken: TakenIn) -> None:
        if self._view.switched_off:  # a rule too slow to test on the records that came
            self.rules_changed()

    @property
    def refiltering(self) -> bool:
        """Rules are being applied to older records (in the background)."""
        return self._view.refiltering

    def stop_filtering(self) -> None:
        """Esc while rules are being applied: switch off the rules not applied yet."""
        with self._table.keeping_position(cursor_line=True):
            stopped = self._view.stop_filtering()
        if stopped:
            described = "; ".join(rule.describe() for rule in stopped)
            self._host.notify(f"Filtering stopped; switched off (r shows the rules): {described}", timeout=8)
            self.rules_changed()

    async def _filter_in_background(self) -> None:
        """Filter the older records in slices, newest first; between slices the event loop
        draws frames and answers keys."""
        await asyncio.sleep(REFILTER_FIRST_PAUSE_S)  # the newest screenful is drawn first
        shown_at = self._clock()
        while True:
            with self._table.keeping_position(cursor_line=True):
                done = self._view.refilter_step(REFILTER_BUDGET_S)
            if self._view.switched_off:
                self.rules_changed()  # filters again under the rules left, in a new worker
                return
            if done:
                break
            if self._clock() - shown_at >= REFILTER_PROGRESS_PERIOD_S:
                shown_at = self._clock()
                self._changed()
            await pause_between_slices(REFILTER_PAUSE_S)
        self.show_counts()
        self._changed()

    def note(self) -> str:
        """What the status line says of the rules: ``2 rules, filtering 40%``."""
        # The level and node toggles' rules have words of their own in the status line.
        entries = [entry for entry in self.rules.entries if not entry.toggle]
        active = sum(1 for entry in entries if entry.active)
        if not active:
            note = "rules off" if entries else ""
            return note + (
                f"{', ' if note else ''}filtering {self._refilter_percent()}%" if self._view.refiltering else ""
            )
        note = plural(active, "rule")
        if self.rules.highlighted_only and self.rules.highlighting:
            note += ", highlighted only"
        if self._view.refiltering:
            note += f", filtering {self._refilter_percent()}%"
        return note

    def _refilter_percent(self) -> int:
        total = max(len(self._store), 1)
        return min(99, int(100 * (1 - self._view.pending / total)))

    def show_counts(self, at_most_every: float = 0.0) -> None:
        """The rules and their counts in the rules pane (not more often than ``at_most_every`` s)."""
        now = self._clock()
        if at_most_every and now - self._counts_at < at_most_every:
            return
        self._counts_at = now
        progress = f"filtering {self._refilter_percent()}%" if self._view.refiltering else ""
        self._rules_pane.show(self.rules, self._view.match_counts(), progress)

    def follow_counts(self) -> None:
        """While the rules pane is open, its counts follow the records (twice a second)."""
        if self._rules_pane.is_open:
            self.show_counts(at_most_every=0.5)

    def apply_initial(self, rules: RuleSet | None, query: str) -> None:
        """The rules and ``--query`` given on the command line."""
        rules = rules or RuleSet()
        if query:
            try:
                rules = rules.with_query(parse_query(query, utc=self._utc))
                self._query_bar.applied_text = query
            except RuleError as error:
                self._host.notify(f"--query not applied: {error.message}", severity="error", timeout=10)
        if rules.entries:
            self.apply_rules(rules)

    def remember(self) -> None:
        """Save the rules in force and the query history for the next run."""
        try:
            save_rules(self.rules, last_rules_path())
            self._query_history.save(query_history_path())
        except OSError:
            pass  # nothing to tell anyone at exit; the rules in force were not lost from the session

    # -- the query line and the rules pane ----------------------------------------------------

    def open_query(self) -> None:
        self._query_bar.open()

    def query_applied(self, message: QueryBar.Applied) -> None:
        self.apply_rules(self.rules.with_query(message.entries))

    def toggle_pane(self) -> None:
        self.show_counts()
        self._rules_pane.toggle()

    def toggle_highlighted_only(self) -> None:
        self.apply_rules(self.rules.with_highlighted_only(not self.rules.highlighted_only))
        state = "on" if self.rules.highlighted_only else "off"
        note = "" if self.rules.highlighting else " (no highlight rule is active, so it hides nothing)"
        self._host.notify(f"Highlighted only: {state}{note}", timeout=4)

    def edit_rule(self, index: int | None) -> None:
        """The rule editor on entry ``index``, or on a new rule."""
        entry = self.rules.entries[index] if index is not None else None

        def edited(result: Entry | None) -> None:
            if result is None:
                return
            rules = self.rules.add(result) if index is None else self.rules.replace(index, result)
            self.apply_rules(rules)

        self._host.push_screen(RuleEditor(entry, utc=self._utc), edited)

    def quick_rule(self, role: str) -> None:
        seqs = self._table.selected_seqs(QUICK_RULE_ROWS)
        if not seqs:
            return

        def chosen(entry: Entry | None) -> None:
            if entry is not None:
                self.apply_rules(self.rules.add(entry))

        self._host.push_screen(QuickRuleScreen([self._store.get(seq) for seq in seqs], Role(role)), chosen)

    def clear_rules(self) -> None:
        self._query_bar.applied_text = ""
        self.apply_rules(RuleSet(highlighted_only=self.rules.highlighted_only))

    # -- rule files ------------------------------------------------------------------------------

    def ask_save(self) -> None:
        def chosen(path: str | None) -> None:
            if not path:
                return
            try:
                save_rules(self.rules, path)
            except OSError as error:
                self._host.notify(f"Rules not saved: {error}", severity="error", timeout=10)
                return
            self._host.notify(f"Saved {plural(len(self.rules.entries), 'rule')} to {path}", timeout=5)

        from ..screens.file_dialogs import PathScreen  # loaded when first opened

        default = os.path.join(os.getcwd(), "console-tui-rules.toml")
        self._host.push_screen(PathScreen("Save the rules to (TOML)", default), chosen)

    def open_rules(self, path: str | None = None) -> None:
        def chosen(path: str | None) -> None:
            if not path:
                return
            try:
                rules = load_rules(path)
            except RuleError as error:
                self._host.notify(
                    f"Rules not loaded, the rules in force stay: {error.message}", severity="error", timeout=15
                )
                return
            self.apply_rules(rules)
            self._host.notify(f"Loaded {plural(len(rules.entries), 'rule')} from {path}", timeout=5)

        if path is not None:
            chosen(path)
        else:
            from ..screens.file_dialogs import PathScreen  # loaded when first opened

            self._host.push_screen(PathScreen("Open rules from (TOML)", "", must_exist=True), chosen)

    def restore_rules(self) -> None:
        path = last_rules_path()
        if not path.exists():
            self._host.notify("No rule set was saved at the end of an earlier run.", timeout=5)
            return
        self.open_rules(str(path))

    COMMANDS: ClassVar[tuple[Command[RulesController], ...]] = (
        Command(
            "console.stop_filtering",
            stop_filtering,
            "escape",
            "Stop a long filtering",
            applies=lambda r: r.refiltering,
        ),
        Command(
            "console.query",
            open_query,
            "slash",
            "Query",
            footer=60,
            about='Type rules as a query: level>=warn node:nav* -node:rviz* +"failed"',
            words="filter",
        ),
        Command(
            "console.rules",
            toggle_pane,
            "r",
            "Rules",
            footer=80,
            about="Show or hide the rules pane: every rule, its switches and counts",
            words="filter",
        ),
        Command(
            "console.add_rule",
            lambda r: r.edit_rule(None),
            title="Add a rule",
            about="A new exclude or highlight rule of any kind",
            words="filter",
        ),
        Command(
            "console.hide_like",
            lambda r: r.quick_rule("exclude"),
            "minus",
            "Hide like the selected rows",
            title="Hide messages like the selected rows",
            about="Exclude their nodes, severities, messages or location",
        ),
        Command(
            "console.highlight_like",
            lambda r: r.quick_rule("highlight"),
            "plus",
            "Highlight like the selected rows",
            title="Highlight messages like the selected rows",
            about="Highlight their nodes, severities, messages or location",
        ),
        Command(
            "console.highlighted_only",
            toggle_highlighted_only,
            "H",
            "Highlighted only",
            about="Show only highlighted messages (or all again)",
        ),
        Command("console.save_rules", ask_save, title="Save rules", about="Save the rule set to a TOML file"),
        Command(
            "console.open_rules", lambda r: r.open_rules(), title="Open rules", about="Load a rule set from a TOML file"
        ),
        Command(
            "console.restore_rules",
            restore_rules,
            title="Restore the last rules",
            about="The rule set in force when console-tui last exited",
        ),
        Command(
            "console.clear_rules",
            clear_rules,
            title="Clear rules",
            about="Remove every rule",
            words="filter",
            ends=True,
        ),
    )
