"""SignalStop: a stop asked for by a signal handler that lands inside the event's own wait."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import threading

from console_tui.system import signal_stop
from console_tui.system.signal_stop import SignalStop

from support.rosproc import wait_until


def test_a_signal_inside_the_events_own_wait_stops_it_at_once():
    stop = SignalStop()
    # The handler runs in the main thread between two bytecodes: here, as inside wait(), the
    # thread holds the event's lock. Event.set() would wait for that lock for ever.
    lock = stop._cond  # the lock threading.Event.wait() holds
    with lock:
        stop.on_signal(signal.SIGTERM, None)
    assert stop.is_set()
    assert stop.wait(0) is True
    assert stop.wait() is True


def test_a_wait_under_way_sees_a_signals_stop_by_its_timeout():
    stop = SignalStop()
    assert stop.wait(0.01) is False
    timer = threading.Timer(0.01, stop.on_signal)
    timer.start()
    timer.join()
    assert stop.wait(0.05) is True  # the flag was set before this wait began
    stop.clear()
    threading.Timer(0.01, stop.on_signal).start()
    assert wait_until(lambda: stop.wait(0.01))  # a wait in progress: by its timeout


def test_a_wait_without_timeout_looks_every_step(monkeypatch):
    monkeypatch.setattr(signal_stop, "STEP_S", 0.01)
    stop = SignalStop()
    threading.Timer(0.02, stop.on_signal).start()
    assert stop.wait() is True


def test_set_and_clear_as_an_event():
    stop = SignalStop()
    stop.set()
    assert stop.is_set() and stop.wait(0)
    stop.clear()
    assert not stop.is_set()
    stop.on_signal()
    stop.clear()
    assert not stop.is_set() and not stop.wait(0)


def test_a_process_in_a_tight_wait_loop_ends_on_every_sigterm():
    """Many SIGTERMs into a process that spins on its stop: each ends it."""
    script = textwrap.dedent(
        """
        import signal, sys
        from console_tui.system.signal_stop import SignalStop
        stop = SignalStop()
        signal.signal(signal.SIGTERM, stop.on_signal)
        print("ready", flush=True)
        while not stop.wait(0):  # a plain Event hangs here on about half the SIGTERMs
            pass
        print("stopped", flush=True)
        """
    )
    for _ in range(20):
        process = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
        assert process.stdout is not None
        assert process.stdout.readline() == "ready\n"
        os.kill(process.pid, signal.SIGTERM)
        assert process.stdout.readline() == "stopped\n"
        assert process.wait(60) == 0
