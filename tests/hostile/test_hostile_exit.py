"""No exit path leaves a temporary logger level set (issue 17): an error inside the app,
SIGTERM, and SIGHUP when the terminal goes away (an SSH session dropping). The console runs
in a real pseudo-terminal, over an in-memory logger control (no ROS: what is tested is the
app's exit, not the services, which tests/ros covers)."""

from __future__ import annotations

import json
import os
import pty
import select
import signal
import sys
import threading
import time
from pathlib import Path
from types import SimpleNamespace

import pytest

PROGRAM = Path(__file__).with_name("console_with_levels.py")


class Console:
    """``console_with_levels.py`` in a pseudo-terminal of its own (its controlling terminal)."""

    def __init__(self, result: Path, mode: str) -> None:
        self.result = result
        pid, fd = pty.fork()
        if pid == 0:  # the child
            os.environ["TERM"] = "xterm-256color"
            os.execv(sys.executable, [sys.executable, str(PROGRAM), str(result), mode])
        self.pid, self.fd = pid, fd
        self.status: int | None = None

    def drain(self, seconds: float) -> None:
        """Read what the app draws (so its writes never block) for ``seconds``."""
        deadline = time.monotonic() + seconds
        while self.fd >= 0 and time.monotonic() < deadline:
            ready, _, _ = select.select([self.fd], [], [], 0.05)
            if ready:
                try:
                    os.read(self.fd, 65536)
                except OSError:
                    return

    def until_ready(self, timeout: float = 30) -> None:
        deadline = time.monotonic() + timeout
        while not (self.result.exists() and "ready" in self.result.read_text()):
            assert time.monotonic() < deadline, "the console never set its temporary level"
            self.drain(0.1)

    def hang_up(self) -> None:
        """Close the terminal's master side: the kernel sends SIGHUP, as when SSH drops."""
        os.close(self.fd)
        self.fd = -1

    def wait(self, timeout: float = 20) -> int:  # exits in 0.3 s; generous for a loaded CI run
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid:
                self.status = status
                return status
            self.drain(0.05) if self.fd >= 0 else time.sleep(0.05)
        os.kill(self.pid, signal.SIGKILL)
        _, self.status = os.waitpid(self.pid, 0)  # reaped: close() has nothing left to kill
        raise AssertionError(f"the console did not exit within {timeout} s")

    def levels_left(self) -> dict[str, int] | None:
        lines = [line for line in self.result.read_text().splitlines() if line.startswith("{")]
        return json.loads(lines[-1])["levels"] if lines else None

    def close(self) -> None:
        if self.fd >= 0:
            os.close(self.fd)
        if self.status is None:
            try:
                os.kill(self.pid, signal.SIGKILL)
                os.waitpid(self.pid, 0)
            except (ChildProcessError, ProcessLookupError):
                pass


@pytest.fixture
def console(tmp_path, request):
    made: list[Console] = []

    def start(mode: str = "signal") -> Console:
        made.append(Console(tmp_path / "result.txt", mode))
        return made[-1]

    yield start
    for each in made:
        each.close()


@pytest.mark.parametrize("how", ["SIGTERM", "SIGHUP (terminal gone)"])
def test_a_signal_puts_temporary_levels_back(console, how):
    app = console()
    app.until_ready()
    if how == "SIGTERM":
        os.kill(app.pid, signal.SIGTERM)
    else:
        app.hang_up()
    status = app.wait()
    assert app.levels_left() == {"": 20, "n": 20}, "the temporary DEBUG level was left on the node"
    assert os.WIFEXITED(status), f"killed by signal {os.WTERMSIG(status)} instead of exiting"


def test_an_error_in_the_app_puts_temporary_levels_back(console):
    app = console("error")
    app.until_ready()
    status = app.wait()
    assert app.levels_left() == {"": 20, "n": 20}
    assert os.WIFEXITED(status)


class _GoneTerminal:
    """A terminal whose other side has closed: every write fails with EIO."""

    def write(self, text: str) -> None:
        raise OSError(5, "Input/output error")

    def flush(self) -> None:
        raise OSError(5, "Input/output error")


def test_the_output_thread_outlives_a_terminal_gone():
    """Textual's output thread died on the first failed write, and the 31st write after it
    blocked the app's exit for ever (a hang-up's exit, 1 in 10)."""
    from textual.drivers._writer_thread import MAX_QUEUED_WRITES, WriterThread

    from console_tui.ui import textual_fixes

    textual_fixes.apply()
    writer = WriterThread(_GoneTerminal())  # type: ignore[arg-type]
    writer.start()
    finished = threading.Event()

    def write_then_stop() -> None:
        for _ in range(MAX_QUEUED_WRITES * 3):
            writer.write("\x1b[?25h")
        writer.stop()
        finished.set()

    threading.Thread(target=write_then_stop, daemon=True).start()
    assert finished.wait(10), "writing to a terminal that is gone blocked"


def test_sigcont_resumes_only_a_suspended_driver():
    """A hang-up brings SIGCONT with SIGHUP: the driver was never suspended, so it is not
    resumed (that started a second output thread and wrote the terminal's modes again)."""
    from console_tui.ui import textual_fixes

    resumed: list[bool] = []
    running = threading.Thread(target=time.sleep, args=(5,), daemon=True)
    running.start()
    driver = SimpleNamespace(_auto_restart=True, resume_application_mode=lambda: resumed.append(True))
    driver._writer_thread = running
    textual_fixes._sigcont_application(driver)  # type: ignore[arg-type]
    assert resumed == [], "a running driver was resumed"
    driver._writer_thread = threading.Thread(target=lambda: None)
    driver._writer_thread.start()
    driver._writer_thread.join()
    textual_fixes._sigcont_application(driver)  # type: ignore[arg-type]
    assert resumed == [True], "a suspended driver (its output thread stopped) was not resumed"
