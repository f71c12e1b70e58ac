"""What a controller asks of the app: to tell the person something, to show a screen, to run
work in the background, later in this turn of the event loop or after the next frame (``ConsoleApp`` is one; a test may pass
anything that does the same)."""

from __future__ import annotations

from collections.abc import Callable
from contextlib import AbstractContextManager
from typing import Any, Protocol

from textual.notifications import SeverityLevel
from textual.screen import Screen
from textual.worker import Worker


class Host(Protocol):
    def notify(
        self,
        message: str,
        *,
        title: str = "",
        severity: SeverityLevel = "information",
        timeout: float | None = None,
        markup: bool = False,
    ) -> None: ...

    def push_screen(self, screen: Screen[Any], callback: Callable[[Any], None] | None = None) -> Any: ...

    def run_worker(
        self,
        work: Any,
        name: str | None = "",
        group: str = "default",
        description: str = "",
        exit_on_error: bool = True,
        start: bool = True,
        exclusive: bool = False,
        thread: bool = False,
    ) -> Worker[Any]: ...

    def call_after_refresh(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> bool: ...

    def call_later(self, callback: Callable[..., Any], *args: Any, **kwargs: Any) -> bool: ...


class TerminalHost(Host, Protocol):
    """A host that can lend the terminal to another program (an editor) and draw again after."""

    def suspend(self) -> AbstractContextManager[None]: ...

    def refresh(self) -> Any: ...
