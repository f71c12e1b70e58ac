"""A stop that a signal handler can ask for without hanging the process.

``threading.Event.set()`` must not run in a signal handler (Python's ``signal`` docs:
"Synchronization primitives such as threading.Lock should not be used within signal
handlers"). The handler runs in the main thread between two bytecodes; when that thread was
inside the same event's ``wait()``, holding the event's lock, which is not re-entrant,
``set()`` waits for itself for ever. The intake process hung like that once in CI, sent
SIGTERM as its app ended (python/cpython#126434 is the same trap in ``multiprocessing``).

``SignalStop`` is an event whose ``on_signal`` is the handler: it only sets a flag, which
``is_set()`` and ``wait()`` read. A ``wait()`` under way sees it by its timeout at the latest
(one without a timeout looks every ``STEP_S``).
"""

from __future__ import annotations

import threading

#: How often a ``wait()`` without a timeout looks for a signal's stop.
STEP_S = 0.1


class SignalStop(threading.Event):
    """An event that threads ``set()`` and signal handlers ask for with ``on_signal``."""

    def __init__(self) -> None:
        super().__init__()
        self._signalled = False

    def on_signal(self, _signum: object = None, _frame: object = None) -> None:
        """A signal handler: ask for the stop, taking no lock."""
        self._signalled = True

    def is_set(self) -> bool:
        return self._signalled or super().is_set()

    def clear(self) -> None:
        self._signalled = False
        super().clear()

    def wait(self, timeout: float | None = None) -> bool:
        if timeout is not None:
            return self.is_set() or super().wait(timeout) or self._signalled
        while not self.is_set():
            super().wait(STEP_S)
        return True
