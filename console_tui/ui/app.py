"""The console-tui Textual app: the keys, and what holds for every screen.

``ConsoleApp`` binds the keys of every command (``command_table``: each controller declares its
own, ``CONTROLLERS`` lists them; the app's own are help and quit): they work and show in the
footer wherever no dialog is open, the keymap remaps them by id, the help screen and the palette
list them, and a key runs its command's row (``action_command``) when the row applies
(``check_action``). The main screen, ``console_screen.ConsoleScreen``, composes the widgets and
owns one controller a concern. The app also keeps what holds for every screen: text from
outside never markup and never raw (notifications, the clipboard), keys typed ahead going where
they were meant (``focus``), the user's keymap, the exit on SIGTERM / SIGHUP, the help screen
and the command palette (``palette``). A new command is a row in its controller's
``COMMANDS``. (docs/decisions/0029-commands-as-data.md says why.)
"""

from __future__ import annotations

import signal
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Protocol

from textual import events
from textual.app import App, SystemCommand
from textual.binding import Binding, BindingType
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
from .command_table import Command, commands_of, key_bindings
from .console_screen import ConsoleScreen
from .controllers.files import FilesController
from .controllers.intake import DRAIN_INTERVAL, Source
from .controllers.jumps import JumpsController
from .controllers.overview import OverviewController
from .controllers.panes import PanesController
from .controllers.rules import RulesController
from .controllers.search import SearchController
from .controllers.table import TableController
from .controllers.toggles import TogglesController
from .controllers.warehouse import WarehouseController
from .exit_signals import ExitSignals, terminal_gone
from .focus import KeyGate, run_bindings_now
from .gc_policy import CollectionPolicy
from .key_groups import key_groups
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


def console_bindings(controllers: Iterable[type], own: Iterable[Command[Any]]) -> list[BindingType]:
    """Every key of the app: Textual's own (Ctrl+Q), the controllers' commands' and the app's,
    the footer's in its order (``key_bindings``)."""
    commands = [*(command for owner in controllers for command in commands_of(owner)), *own]
    textual = [binding for binding in App.BINDINGS if not isinstance(binding, Binding) or binding.key != "ctrl+c"]
    # Ctrl+C quits too, as a terminal's interrupt (not in the footer, not remapped).
    return [*textual, *key_bindings(commands), Binding("ctrl+c", "quit", "Quit", show=False)]


# Not inherited: BINDINGS is every key, in order (a console with other controllers binds them
# all again, its new ones in their places).
class ConsoleApp(App[None], inherit_bindings=False):
    """Every log message in one table, fed by sources through an ``IntakeQueue``."""

    TITLE = "console-tui"
    #: By its whole path: a console with other controllers (a subclass elsewhere) finds it too.
    CSS_PATH = str(Path(__file__).with_name("app.tcss"))
    #: Textual's own palette entries (theme, quit, screenshot...) and ours.
    COMMANDS = App.COMMANDS | {PaletteProvider}

    #: The controllers whose commands the keys, the footer, the help screen and the palette
    #: show, in the order the help screen and the palette list them; the main screen makes
    #: each (one that needs only the ``ConsoleContext`` is made as ``Controller(context)``).
    CONTROLLERS: ClassVar[tuple[type, ...]] = (
        TableController,
        FilesController,
        RulesController,
        SearchController,
        PanesController,
        OverviewController,
        JumpsController,
        TogglesController,
        WarehouseController,
    )

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
        self.key_gate = KeyGate(self)
        #: The screen of the log table, with the controllers the commands run on.
        self.main = ConsoleScreen(
            self,
            controllers=self.CONTROLLERS,
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
        #: Every command (``command_table``): the controllers', then the app's own.
        self.commands = self.main.commands
        self.commands.add(self, self.APP_COMMANDS)
        self._keymap_problems = self._load_keymap(keymap_file)

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

    def begin_quitting(self) -> None:
        """``q``: the sources stop while Textual takes the screens down."""
        self.main.intake.begin_stopping_sources()
        self.exit()

    async def action_quit(self) -> None:  # Ctrl+C, and the palette's Quit (Textual's)
        self.begin_quitting()

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

    # -- the commands (``command_table``): every key, the footer, the help screen, the palette ------

    def action_command(self, command_id: str) -> None:
        """Run a command of the command table (its key's action, its palette entry's)."""
        self.commands.run(command_id)

    def check_action(self, action: str, parameters: tuple[object, ...]) -> bool | None:
        if action == "command" and parameters:
            return self.commands.applies(str(parameters[0]))
        return True

    def show_help(self) -> None:
        # Not an ``applies``: the footer under the help screen keeps its key, as it always did.
        if not isinstance(self.screen, HelpScreen):
            self.push_screen(HelpScreen(self.binding_groups()))

    def binding_groups(self) -> list[tuple[str, list[Binding]]]:
        """Every key, by where it works: the help screen, the keymap and the palette read these."""
        return key_groups(self.commands)

    #: The app's own commands (the controllers' are theirs: ``CONTROLLERS``).
    APP_COMMANDS: ClassVar[tuple[Command[ConsoleApp], ...]] = (
        Command(
            "console.help",
            show_help,
            "question_mark,f1",
            "Help",
            footer=120,
            title="Help: every key",
            about="What console-tui shows, and every key (remap them in keys.toml)",
        ),
        Command("console.quit", lambda app: app.begin_quitting(), "q", "Quit", footer=130),
    )

    #: Every command's keys, read from the rows.
    BINDINGS = console_bindings(CONTROLLERS, APP_COMMANDS)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        # A console with other controllers (``CONTROLLERS``) binds their keys.
        cls.BINDINGS = console_bindings(cls.CONTROLLERS, cls.APP_COMMANDS)
        super().__init_subclass__(**{"inherit_bindings": False, **kwargs})

    def get_system_commands(self, screen: Screen) -> Iterable[SystemCommand]:
        # Textual's "Keys" opens its key panel; "Help: every key" (ours) says more.
        yield from (command for command in super().get_system_commands(screen) if command.title != "Keys")
