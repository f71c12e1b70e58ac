"""What every part of the app uses of ``ConsoleApp``: the store, the view, the table, the clock.

``ConsoleApp`` is put together from parts by subject (``rule_actions``, ``file_actions``,
``table_actions``, ...), each a class it mixes in. A part subclasses ``AppPart`` for the state
they all share, typed once here, and names beside its own methods whatever else it uses of
the app.
"""

from __future__ import annotations

from collections.abc import Callable

from textual.app import App

from ..model.store import LogStore
from ..model.view import LogView
from .widgets.log_table import LogTable


class AppPart(App[None]):
    """The state the app's parts share (``ConsoleApp`` sets it)."""

    store: LogStore
    #: The rows shown: the store under the rules in force.
    view: LogView
    table: LogTable
    #: Times shown in UTC rather than local time.
    utc: bool
    #: Seconds, for rates and for how often things are redrawn (``time.monotonic``; tests set it).
    clock: Callable[[], float]
    #: The status line shows the facts of now.
    update_status: Callable[[], None]
