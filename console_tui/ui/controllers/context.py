"""What every controller of the console works on: one ``ConsoleContext``, made by the screen.

A controller is made with the context and the few things only it drives (its widgets, its
pane's state); it keeps what it uses of the context, and tells the console its state changed
with ``changed()`` (the status line and the footer are drawn again, once, after the turn of
the event loop that changed them) instead of drawing the status line itself.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from ...model.store.log_store import LogStore
from ...model.view.log_view import LogView
from ...model.view.marks import Marks
from ..widgets.log_table import LogTable
from .announcements import Announcements
from .host import TerminalHost


@dataclass(frozen=True)
class ConsoleContext:
    #: The app: notify, show a screen, run work in the background, lend the terminal.
    host: TerminalHost
    store: LogStore
    #: The rows the rules show.
    view: LogView
    table: LogTable
    marks: Marks
    #: The app's clock (seconds): budgets, periods, rates.
    clock: Callable[[], float]
    #: Times in UTC, as the command line said.
    utc: bool
    #: Say the console's state changed: the status line (and the footer's keys that come and
    #: go) are drawn again, once however many changes come in one turn of the event loop.
    changed: Callable[[], None]
    #: Records taken in, rules changed, the store cleared: announced here, followed by subscribers.
    announce: Announcements
