"""The console-tui Textual app: the keys, and what holds for every screen.

``ConsoleApp`` holds the keys (``BINDINGS``, from ``app_bindings``: they work and show in the
footer wherever no dialog is open, the keymap remaps them, the help screen and the palette list
them) and its actions, each a line handing over to a controller of the main screen,
``console_screen.ConsoleScreen``: it composes the widgets and owns one controller a concern
(``controllers``: intake, table, rules, files, panes, search, jumps, toggles, overview). The app
also keeps what holds for every screen: text from outside never markup and never raw
(notifications, the clipboard), keys typed ahead going where they were meant (``focus``), the
user's keymap, the exit on SIGTERM / SIGHUP, the help screen and the command palette
(``palette``). A feature adds its keys to ``app_bindings``, its action here, its work in a
controller of its own. (docs/decisions/0020-app-as-controllers.md says why.)
"""

from __future__ import annotations

import signal
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

from textual import events
from textual.app import App, SystemCommand
from textual.binding import Binding
from textual.notifications import SeverityLevel
from textual.screen import Screen

from ..model.inert_text import multi_line, one_line
from ..model.rules.history import QueryHistory
from ..model.rules.ruleset import RuleSet
from ..model.rules.rulesfile import query_history_path
from ..model.store.intake_queue import IntakeQueue
from ..model.store.log_store import LogStore
from ..ros.fleet import Robot
from . import textual_fixes
from .app_bindings import APP_BINDINGS, NAV_KEYS, bindings_of, key_groups
from .console_screen import ConsoleScreen
from .controllers.intake import DRAIN_INTERVAL, Source
from .exit_signals import ExitSignals, terminal_gone
from .focus import KeyGate, run_bindings_now
from .gc_policy import CollectionPolicy
from .keys import binding_ids, keymap_path, load_keymap
from .palette import PaletteProvider
from .screens.help import HelpScreen

if TYPE_CHECKING:
    from ..control.control_thread import LoggerControl

textual_fixes.apply()


class TerminalGuard(Protocol):
    """Something holding the terminal's descriptors that lets go while the app is suspended."""

    def pause(self) -> None: ...

    def resume(self) -> None: ...


class ConsoleApp(App[None]):
    """Every log message in one table, fed by sources through an ``IntakeQueue``."""

    TITLE = "console-tui"
    CSS_PATH = "app.tcss"
    #: Textual's own palette entries (theme, quit, screenshot...) and ours.
    COMMANDS = App.COMMANDS | {PaletteProvider}

    #: Every key of the console (``app_bindings``; the help screen groups them).
    BINDINGS = APP_BINDINGS

    def __init__(
        self,
        *,
        store: LogStore | None = None,
        queue: IntakeQueue | None = None,
        sources: Sequence[Source] = (),
        utc: bool = False,
        drain_interval: float = DRAIN_INTERVAL,
        clock: Callable[[], float] = time.monotonic,
        files: Sequence[str] = (),
        log_format: str | None = None,
        logger_control: LoggerControl | None = None,
        rules: RuleSet | None = None,
        query: str = "",
        remember_rules: bool = False,
        keymap_file: str | None = None,
        robots: Sequence[Robot] = (),
        file_robots: Mapping[str, str] | None = None,
    ) -> None:
        super().__init__()
        self.collection_policy = CollectionPolicy(delay=drain_interval / 2)
        #: Keep the last rule set and the query history in the user's config folder.
        self.remember_rules_at_exit = remember_rules
        #: Started after the first frame with the sources; whoever made it closes it.
        self.logger_control = logger_control
        self.exit_signals = ExitSignals(self._exit_on_signal)
        #: Binding id -> keys, from the user's keys.toml (the keys the screen names follow it).
        self.keymap: dict[str, str] = {}
        self._keymap_problems = self._load_keymap(keymap_file)
        self.key_gate = KeyGate(self)
        #: The screen of the log table, with the controllers the actions below hand over to.
        self.main = ConsoleScreen(
            self,
            store=store if store is not None else LogStore(),
            queue=queue if queue is not None else IntakeQueue(),
            sources=sources,
            utc=utc,
            clock=clock,
            drain_interval=drain_interval,
            collection_policy=self.collection_policy,
            query_history=QueryHistory.load(query_history_path()) if remember_rules else QueryHistory(),
            files=files,
            log_format=log_format,
            logger_control=logger_control,
            rules=rules,
            query=query,
            robots=robots,
            file_robots=file_robots,
        )

    def get_default_screen(self) -> Screen:
        return self.main

    # -- text from outside: never markup, never raw ----------------------------------------------

    def notify(
        self,
        message: str,
        *,
        title: str = "",
        severity: SeverityLevel = "information",
        timeout: float | None = None,
        markup: bool = False,
    ) -> None:
        """Every notification (ours, the screens', Textual's) as plain, inert text: messages
        name files, nodes and errors from outside, which may hold markup or escapes."""
        super().notify(multi_line(message), title=one_line(title), severity=severity, timeout=timeout, markup=False)

    #: What catches native code's output while the app draws (``system.native_output``): put
    #: aside while the app is suspended (an editor has the terminal). Set by ``run_app``.
    native_output: TerminalGuard | None = None

    @contextmanager
    def suspend(self) -> Iterator[None]:
        guard = self.native_output
        if guard is not None:
            guard.pause()
        try:
            with super().suspend():
                yield
        finally:
            if guard is not None:
                guard.resume()

    def copy_to_clipboard(self, text: str) -> None:
        """Copy with control characters made visible (newlines and tabs kept): pasted into a
        shell, a copied message can never carry escape sequences or a carriage return."""
        super().copy_to_clipboard(multi_line(text))

    def on_mount(self) -> None:
        self.exit_signals.install()
        if not self.is_headless and sys.__stdin__ is not None and sys.__stdin__.isatty():
            self.set_interval(1.0, self._watch_terminal)
        if self._keymap_problems:
            listed = "\n".join(self._keymap_problems[:5])
            self.notify(f"Some keys were not remapped:\n{listed}", severity="warning", timeout=15, markup=False)

    def _load_keymap(self, keymap_file: str | None) -> tuple[str, ...]:
        """The user's keymap, in force before the widgets compose (their hints name its keys)."""
        path = keymap_path() if keymap_file is None else Path(keymap_file)
        loaded = load_keymap(path, lambda: binding_ids(self.binding_groups()))
        if loaded.keys:
            self.keymap = loaded.keys
            self.set_keymap(loaded.keys)
        return loaded.problems

    def on_unmount(self) -> None:
        self.exit_signals.remove()
        self.main.intake.stop_sources()
        if self.remember_rules_at_exit:
            self.main.filtering.remember()
        self.main.files.cancel_loads()

    def _watch_terminal(self) -> None:
        """A hung-up terminal whose SIGHUP never came: end as on SIGHUP (``exit_signals``)."""
        if terminal_gone(sys.__stdin__.fileno()):  # type: ignore[union-attr]
            self._exit_on_signal(signal.SIGHUP)

    def _exit_on_signal(self, signum: int) -> None:
        """SIGTERM or SIGHUP (the SSH session dropped): put temporary logger levels back
        first, whatever becomes of the terminal, then exit as ``q`` does."""
        if self.logger_control is not None:
            try:
                self.logger_control.close()
            except Exception:
                pass
        self.main.intake.begin_stopping_sources()
        self.exit(return_code=128 + signum)

    async def action_quit(self) -> None:
        self.main.intake.begin_stopping_sources()
        self.exit()

    async def on_event(self, event: events.Event) -> None:
        # Keys typed ahead go where they were meant (see focus.py): they wait while the screen
        # on top is not ready for them, and while the table has the focus a key's binding runs
        # at once, so that the keys behind it find the focus where it put it.
        if isinstance(event, events.Key) and not event.is_forwarded:
            if self.key_gate.hold(event):
                return
            if self.focused is self.main.table and await run_bindings_now(self, event):
                return
        await super().on_event(event)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        return self.main.key_applies(action)

    # -- the table (``controllers.table``) -------------------------------------------------------

    def action_pause(self) -> None:
        self.main.table.set_paused(True)

    def action_resume(self) -> None:
        self.main.table.set_paused(False)

    def action_toggle_pause(self) -> None:
        self.main.table.set_paused(self.main.table.paused_end is None)

    def action_follow(self) -> None:
        self.main.table.follow()

    def action_clear(self) -> None:
        self.main.table_control.clear()

    def action_columns(self) -> None:
        self.main.table_control.ask_columns()

    def action_toggle_column(self, key: str) -> None:
        self.main.table_control.toggle_column(key)

    def action_details(self) -> None:
        self.main.table.action_activate()

    # -- rules (``controllers.rules``) -----------------------------------------------------------

    def action_query(self) -> None:
        self.main.query_bar.open()

    def action_toggle_rules(self) -> None:
        self.main.filtering.toggle_pane()

    def action_stop_filtering(self) -> None:
        self.main.filtering.stop_filtering()

    def action_toggle_highlighted_only(self) -> None:
        self.main.filtering.toggle_highlighted_only()

    def action_add_rule(self) -> None:
        self.main.filtering.edit_rule(None)

    def action_quick_rule(self, role: str) -> None:
        self.main.filtering.quick_rule(role)

    def action_clear_rules(self) -> None:
        self.main.filtering.clear_rules()

    def action_save_rules(self) -> None:
        self.main.filtering.ask_save()

    def action_load_rules(self, path: str | None = None) -> None:
        self.main.filtering.open_rules(path)

    def action_restore_rules(self) -> None:
        self.main.filtering.restore_rules()

    # -- files (``controllers.files``) -----------------------------------------------------------

    def action_open(self) -> None:
        self.main.files.ask_open()

    def action_cancel_load(self) -> None:
        self.main.files.cancel_loads()

    def action_problems(self) -> None:
        self.main.files.show_problems()

    def action_save(self) -> None:
        self.main.files.ask_save()

    # -- toggles (``controllers.toggles``) and the side panes (``controllers.panes``) ---------------

    def action_toggle_level(self, level: int) -> None:
        self.main.toggles.toggle_level(level)

    def action_raise_minimum(self) -> None:
        self.main.toggles.raise_minimum()

    def action_lower_minimum(self) -> None:
        self.main.toggles.lower_minimum()

    def action_all_levels(self) -> None:
        self.main.toggles.all_levels()

    def action_minimum_level(self, level: int) -> None:
        self.main.toggles.minimum_level(level)

    def action_solo_row_node(self) -> None:
        self.main.toggles.solo_row_node()

    def action_mute_row_node(self) -> None:
        self.main.toggles.mute_row_node()

    def action_clear_node_toggles(self) -> None:
        self.main.toggles.clear_node_toggles()

    def action_next_time_format(self) -> None:
        self.main.toggles.next_time_format()

    def action_time_format(self, name: str) -> None:
        self.main.toggles.time_format(name)

    def action_toggle_utc(self) -> None:
        self.main.toggles.toggle_utc()

    def action_toggle_loggers(self) -> None:
        self.main.panes.toggle_loggers()

    def action_toggle_nodes(self) -> None:
        self.main.panes.toggle_nodes()

    def action_loggers_for_row(self) -> None:
        self.main.panes.loggers_for_row()

    # -- the overview (``controllers.overview``) -------------------------------------------------

    def action_toggle_timeline(self) -> None:
        self.main.overview.toggle_timeline()

    def action_timeline(self) -> None:
        self.main.overview.pick_time()

    def action_toggle_storm(self) -> None:
        self.main.overview.toggle_storm()

    def action_toggle_storms(self) -> None:
        self.main.overview.toggle_storms()

    def action_toggle_mask_digits(self) -> None:
        self.main.overview.toggle_mask_digits()

    def action_summary(self) -> None:
        from .screens.summary import SummaryScreen  # loaded when first opened

        if not isinstance(self.screen, SummaryScreen):
            self.main.overview.summary()

    # -- search (``controllers.search``) --------------------------------------------------------

    def action_search(self) -> None:
        self.main.searching.open_search_line()

    def action_clear_search(self) -> None:
        if self.main.searching.search is not None:
            self.main.searching.clear_search()

    def action_next_match(self) -> None:
        self.main.searching.jump_to_match(forward=True)

    def action_previous_match(self) -> None:
        self.main.searching.jump_to_match(forward=False)

    # -- jumps (``controllers.jumps``) ---------------------------------------------------------

    def action_next_level(self, level: int) -> None:
        self.main.jumps.next_level(level)

    def action_previous_level(self, level: int) -> None:
        self.main.jumps.previous_level(level)

    def action_first_row(self) -> None:
        self.main.table.action_first_row()

    def action_last_row(self) -> None:
        self.main.table.follow()

    def action_toggle_mark(self) -> None:
        self.main.jumps.toggle_mark()

    def action_next_mark(self) -> None:
        self.main.jumps.to_mark(forward=True)

    def action_previous_mark(self) -> None:
        self.main.jumps.to_mark(forward=False)

    def action_marks(self) -> None:
        self.main.jumps.list_marks()

    def action_open_source(self) -> None:
        self.main.jumps.open_source()

    # -- help and the command palette -------------------------------------------------------------

    def action_help(self) -> None:
        if isinstance(self.screen, HelpScreen):
            return
        self.push_screen(HelpScreen(self.binding_groups()))

    def binding_groups(self) -> list[tuple[str, list[Binding]]]:
        """Every key, by where it works: the help screen, the keymap and the palette read these."""
        return key_groups()

    def nav_bindings(self) -> list[Binding]:
        """The keys that find your way: search, jumps, marks, levels, nodes, time (the search
        line's hint names them)."""
        return bindings_of(NAV_KEYS)

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        # Textual's "Keys" opens its key panel; "Help: every key" (ours) says more.
        yield from (command for command in super().get_system_commands(screen) if command.title != "Keys")
