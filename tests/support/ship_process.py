"""``console-tui ship`` run as a process, as on a robot: its status lines read as they come,
stopped with SIGTERM (as systemd does), or killed with SIGKILL."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

from support.rosproc import PATIENCE_S


class ShipProcess:
    def __init__(self, env: dict[str, str], url: str, spool: Path, *args: str) -> None:
        self.process = subprocess.Popen(
            [sys.executable, "-m", "console_tui", "ship", url, "--spool", str(spool), "--status-every", "0.3", *args],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            env=env,
            text=True,
            start_new_session=True,
        )
        self.lines: list[str] = []
        self._lock = threading.Lock()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        for line in self.process.stderr:
            with self._lock:
                self.lines.append(line.rstrip("\n"))

    def text(self) -> str:
        with self._lock:
            return "\n".join(self.lines)

    def wait_for(self, condition, timeout: float = PATIENCE_S, what: str = "the shipper") -> str:
        """Until ``condition(last line)`` holds for a status line; that line."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self._lock:
                lines = list(self.lines)
            for line in reversed(lines):
                if condition(line):
                    return line
            if self.process.poll() is not None and not lines:
                break
            time.sleep(0.1)
        raise AssertionError(f"timed out waiting for {what}; it said:\n{self.text()[-3000:]}")

    def stop(self, timeout: float = 30.0) -> int:
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.kill()
        return self.process.wait()

    def kill(self) -> None:
        """SIGKILL, to its child (the intake process) too, as a crash takes both."""
        if self.process.poll() is None:
            os.killpg(self.process.pid, signal.SIGKILL)
        self.process.wait()


def number_after(line: str, word: str) -> int:
    """The number written after ``word`` in a status line (``sent 1,200,`` -> 1200); -1 in a
    line that is no status line."""
    for part in re.split(r"[;,] ", line.split("ship: ", 1)[-1]):
        part = part.strip()
        if part.startswith(word + " "):
            return int(part.split()[1].replace(",", ""))
    return -1
