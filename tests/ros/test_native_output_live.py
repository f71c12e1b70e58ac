"""``console-tui`` in a terminal of its own, with Fast DDS printing an error straight to the
process's stderr as the app's own participant starts, when the logger levels pane opens (a
profile file that does not exist): the text is a row in the table, never raw on the screen,
and is written on stderr again after the app has ended."""

from __future__ import annotations

import os
import pty
import select
import signal
import sys
import time

import pytest

pytestmark = pytest.mark.ros2

FAST_DDS_RAW = b"\x1b[31;1m[\x1b[37;1mXMLPARSER"  # how Fast DDS colours it on a terminal


class Terminal:
    def __init__(self, argv: list[str], env: dict[str, str]) -> None:
        pid, fd = pty.fork()
        if pid == 0:  # the child
            os.environ.clear()
            os.environ.update(env)
            os.execv(argv[0], argv)
        self.pid, self.fd = pid, fd
        self.output = b""

    def read_until(self, wanted: bytes, timeout: float = 30) -> bool:
        deadline = time.monotonic() + timeout
        while wanted not in self.output and time.monotonic() < deadline:
            ready, _, _ = select.select([self.fd], [], [], 0.05)
            if ready:
                try:
                    chunk = os.read(self.fd, 65536)
                except OSError:
                    break
                if not chunk:
                    break
                self.output += chunk
        return wanted in self.output

    def wait(self, timeout: float = 20) -> int:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            self.read_until(b"\0never", 0.1)
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid:
                return os.waitstatus_to_exitcode(status)
        os.kill(self.pid, signal.SIGKILL)
        raise AssertionError("console-tui did not end")


def test_what_fast_dds_prints_is_a_row_and_never_raw(ros_env, tmp_path):
    env = {
        **os.environ,
        **ros_env,
        "TERM": "xterm-256color",
        "COLUMNS": "160",
        "LINES": "30",
        "XDG_CONFIG_HOME": str(tmp_path),
        "FASTDDS_DEFAULT_PROFILES_FILE": str(tmp_path / "missing.xml"),
        "FASTRTPS_DEFAULT_PROFILES_FILE": str(tmp_path / "missing.xml"),  # Jazzy's Fast DDS 2.14 reads this one
    }
    console = Terminal([sys.executable, "-m", "console_tui.cli", "--topic", "/rosout"], env)
    assert console.read_until(b"FOLLOW"), console.output[-2000:]
    os.write(console.fd, b"l")  # the logger levels pane: the app joins the graph
    assert console.read_until(b"XMLPARSER Error"), console.output[-2000:]
    os.write(console.fd, b"l")  # closed again: the table's message cells as wide as they were
    assert console.read_until(b"realpath failed"), console.output[-2000:]  # in the table's message cell
    os.write(console.fd, b"q")
    assert console.wait() == 0
    assert b"printed in this process while the console ran" in console.output
    assert FAST_DDS_RAW not in console.output, "Fast DDS's own text reached the terminal"
