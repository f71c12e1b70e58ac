"""SIGTERM and SIGHUP end the app as ``q`` does, so that nothing it set is left behind.

By default either signal kills the process on the spot: a temporary logger level would stay
set on its node, and the terminal in the app's mode. A hangup comes when the SSH session
drops. Here each becomes a callback on the event loop (``loop.add_signal_handler``), and
the handlers that were there before come back when the app ends.

A terminal can also go away without a hangup reaching us (the session leader, a shell that
ignores SIGHUP, outlives it): reads then return nothing at once and Textual's input thread
spins a core for ever. ``terminal_gone`` tells, once a second, and the app ends as on SIGHUP.
"""

from __future__ import annotations

import asyncio
import errno
import signal
import termios
import threading
from collections.abc import Callable
from typing import Any

EXIT_SIGNALS = (signal.SIGTERM, signal.SIGHUP)


class ExitSignals:
    """Calls ``on_signal(signum)`` on the running loop for SIGTERM and SIGHUP while installed."""

    def __init__(self, on_signal: Callable[[int], None]) -> None:
        self.on_signal = on_signal
        self._previous: dict[int, Any] = {}
        self._loop: asyncio.AbstractEventLoop | None = None

    def install(self) -> None:
        if threading.current_thread() is not threading.main_thread():
            return  # signals reach only the main thread
        loop = asyncio.get_running_loop()
        for signum in EXIT_SIGNALS:
            previous = signal.getsignal(signum)
            try:
                loop.add_signal_handler(signum, self.on_signal, int(signum))
            except (NotImplementedError, RuntimeError, ValueError):
                continue
            self._previous[signum] = previous
        self._loop = loop

    def remove(self) -> None:
        loop, self._loop = self._loop, None
        for signum, previous in self._previous.items():
            if loop is not None and not loop.is_closed():
                loop.remove_signal_handler(signum)
            signal.signal(signum, previous if previous is not None else signal.SIG_DFL)
        self._previous.clear()


def terminal_gone(fd: int) -> bool:
    """Whether the terminal on ``fd`` was hung up: its attributes can no longer be read (EIO)."""
    try:
        termios.tcgetattr(fd)
    except termios.error as error:
        return bool(error.args) and error.args[0] in (errno.EIO, errno.ENXIO, errno.EBADF)
    except (OSError, ValueError):
        return True
    return False
