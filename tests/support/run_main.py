"""Running ``console-tui`` in this process, as ``cli.main`` does, with the terminal swapped for
a headless one of a fixed size and a script that reads the screen and presses keys."""

from __future__ import annotations

import os
from collections.abc import Awaitable, Callable

import pytest

from console_tui.cli import main
from console_tui.ui.app import ConsoleApp

Script = Callable[[object], Awaitable[None]]


def run_main(monkeypatch: pytest.MonkeyPatch, argv: list[str], script: Script, size=(120, 30)) -> tuple[int, list]:
    """``cli.main(argv)`` with every ``ConsoleApp.run`` headless, driven by ``script(pilot)``
    (which must end the app, with ``q`` as a person does). Returns the exit code and the
    apps that ran. The process environment is put back afterwards (a run sets some
    ROS variables, as it does for a real run)."""
    apps: list[ConsoleApp] = []
    failures: list[BaseException] = []
    original = ConsoleApp.run
    saved_environment = dict(os.environ)

    async def guarded(pilot) -> None:
        try:
            await script(pilot)
        except BaseException as error:  # reported after the app has ended
            failures.append(error)
            pilot.app.exit(return_code=99)

    def run_headless(self, *args, **kwargs):
        apps.append(self)
        return original(self, headless=True, size=size, auto_pilot=guarded)

    monkeypatch.setattr(ConsoleApp, "run", run_headless)
    try:
        code = main(argv)
    finally:
        os.environ.clear()
        os.environ.update(saved_environment)
    if failures:
        raise failures[0]
    return code, apps
