"""Starting real node processes for tests, and stopping every one of them."""

from __future__ import annotations

import importlib.util
import json
import os
import queue
import subprocess
import sys
import threading
import time
from collections import deque
from pathlib import Path
from typing import Any

NODES = Path(__file__).parent.parent / "nodes"
#: The longest a test waits for something to happen (a node to start, discovery, a message):
#: generous, for a machine busy with other work; a wait ends as soon as its condition holds.
PATIENCE_S = 60.0


def ros_available() -> bool:
    return importlib.util.find_spec("rclpy") is not None


class NodeProcess:
    """A node script from ``tests/nodes`` in a child process.

    The script prints one JSON object per line on stdout; ``READY`` objects and others
    are read with ``expect``. Closing its stdin (``stop``) ends it; ``kill`` does not wait.
    Its stderr (where rclpy prints every log message) is read all the time, its tail kept:
    a full pipe would block the node's logging, and with it the whole node.
    """

    def __init__(
        self,
        script: str,
        *args: str,
        env: dict[str, str],
        python: str = sys.executable,
        command: list[str] | None = None,
    ) -> None:
        """Runs ``python -u tests/nodes/SCRIPT ARGS``, or ``command + ARGS`` when given."""
        self.process = subprocess.Popen(
            [*(command or [python, "-u", str(NODES / script)]), *args],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=env,
            text=True,
        )
        self.lines: list[dict[str, Any]] = []
        self.stderr_tail: deque[str] = deque(maxlen=50)
        #: ``{text: lines of stderr that held it}`` for each text given to ``count_stderr``.
        self.stderr_counts: dict[str, int] = {}
        # Both streams are read by threads: selecting on a buffered pipe misses lines
        # already in the buffer, and an unread stderr pipe fills up and blocks the node.
        self._incoming: queue.Queue[dict[str, Any] | None] = queue.Queue()
        threading.Thread(target=self._read_stdout, daemon=True).start()
        self._stderr_reader = threading.Thread(target=self._read_stderr, daemon=True)
        self._stderr_reader.start()

    def expect(self, key: str, timeout: float = PATIENCE_S) -> dict[str, Any]:
        """Read stdout until an object with ``"event": key`` arrives; return it."""
        for line in self.lines:
            if line.get("event") == key:
                return line
        deadline = time.monotonic() + timeout
        while (remaining := deadline - time.monotonic()) > 0:
            try:
                item = self._incoming.get(timeout=remaining)
            except queue.Empty:
                break
            if item is None:  # the end of stdout: the process is gone
                self._incoming.put(None)
                break
            self.lines.append(item)
            if item.get("event") == key:
                return item
        if self.process.poll() is not None:
            self._stderr_reader.join(2.0)
        stderr = "".join(self.stderr_tail)
        raise TimeoutError(f"{self.process.args[:3]} never said {key!r}; stderr: {stderr[-2000:]}")

    def _read_stdout(self) -> None:
        assert self.process.stdout is not None
        for raw in self.process.stdout:
            try:
                self._incoming.put(json.loads(raw))
            except json.JSONDecodeError:
                continue
        self._incoming.put(None)

    def _read_stderr(self) -> None:
        assert self.process.stderr is not None
        for line in self.process.stderr:
            self.stderr_tail.append(line)
            for text in list(self.stderr_counts):
                if text in line:
                    self.stderr_counts[text] += 1

    def count_stderr(self, *texts: str) -> None:
        """From now on, count the lines of stderr that hold each text (``stderr_counts``):
        the tail keeps only the last lines."""
        for text in texts:
            self.stderr_counts.setdefault(text, 0)

    def expect_next(self, key: str, timeout: float = PATIENCE_S) -> dict[str, Any]:
        """Like ``expect``, but only an object that was not read before."""
        self.lines = [line for line in self.lines if line.get("event") != key]
        return self.expect(key, timeout)

    def send(self, command: dict[str, Any]) -> None:
        assert self.process.stdin is not None
        self.process.stdin.write(json.dumps(command) + "\n")
        self.process.stdin.flush()

    def stop(self, timeout: float = 5.0) -> None:
        if self.process.poll() is None:
            try:
                assert self.process.stdin is not None
                self.process.stdin.close()
            except (BrokenPipeError, OSError):
                pass
            try:
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait(timeout)

    def kill(self) -> None:
        self.process.kill()
        self.process.wait(5)


class NodeProcesses:
    """Every node process a test started, stopped at the end whatever happens."""

    def __init__(self, env: dict[str, str]) -> None:
        self.env = env
        self.started: list[NodeProcess] = []

    def start(self, script: str, *args: str) -> NodeProcess:
        return self.add(NodeProcess(script, *args, env=self.env))

    def add(self, process: NodeProcess) -> NodeProcess:
        """``process``, stopped with the others at the end."""
        self.started.append(process)
        return process

    def stop_all(self) -> None:
        for process in self.started:
            process.stop()
        self.started.clear()


def wait_until(condition, timeout: float = PATIENCE_S, interval: float = 0.05) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(interval)
    return bool(condition())


def pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    return True


def group_alive(group: int) -> bool:
    """Whether any process of the process group ``group`` is still running."""
    try:
        os.killpg(group, 0)
    except OSError:
        return False
    return True


class BusyProcesses:
    """``count`` processes that only spin, to load the machine while a test runs (a context
    manager: they are killed at the end)."""

    def __init__(self, count: int = 1) -> None:
        self.count = count
        self.processes: list[subprocess.Popen] = []

    def __enter__(self) -> BusyProcesses:
        for _ in range(self.count):
            self.processes.append(subprocess.Popen([sys.executable, "-c", "while True: pass"]))
        return self

    def __exit__(self, *_exc: object) -> None:
        for process in self.processes:
            process.kill()
            process.wait(5)
