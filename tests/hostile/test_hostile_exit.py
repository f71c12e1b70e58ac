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
import time
from pathlib import Path

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

    def wait(self, timeout: float = 40) -> int:  # loaded CI with coverage: once over 20 s
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
