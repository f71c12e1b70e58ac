"""``console-tui tail`` run as a process: its output lines read by a thread (select misses
lines already buffered), its stderr kept, stopped with SIGINT as at a terminal."""

from __future__ import annotations

import queue
import signal
import subprocess
import sys
import threading
import time

from support.rosproc import PATIENCE_S


class TailProcess:
    def __init__(self, env: dict[str, str], *args: str) -> None:
        self.process = subprocess.Popen(
            [sys.executable, "-m", "console_tui", "tail", *args],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=env,
        )
        self.lines: queue.Queue[bytes | None] = queue.Queue()
        self.stderr: list[bytes] = []
        self._readers = [
            threading.Thread(target=self._read, daemon=True),
            threading.Thread(target=lambda: self.stderr.extend(self.process.stderr), daemon=True),
        ]
        for reader in self._readers:
            reader.start()

    def _read(self) -> None:
        for line in self.process.stdout:
            self.lines.put(line)
        self.lines.put(None)

    def take(self, count: int, timeout: float = PATIENCE_S) -> list[bytes]:
        """The next ``count`` lines, ``\\n`` and all; fewer when it ends or ``timeout`` passes."""
        got: list[bytes] = []
        deadline = time.monotonic() + timeout
        while len(got) < count and (left := deadline - time.monotonic()) > 0:
            try:
                line = self.lines.get(timeout=left)
            except queue.Empty:
                break
            if line is None:
                break
            got.append(line)
        return got

    def take_text(self, count: int, timeout: float = PATIENCE_S) -> list[str]:
        """``take``, decoded, without the ``\\n``."""
        return [line.decode().rstrip("\n") for line in self.take(count, timeout)]

    def stop(self, timeout: float = 15) -> int:
        """SIGINT, then SIGKILL after ``timeout``; its exit status, with all of stderr read."""
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        for reader in self._readers:
            reader.join(5)
        return self.process.returncode
