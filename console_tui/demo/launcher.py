"""Starting and stopping the demo node processes."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
import time

from ..model.inert_text import plural
from ..sources.status import SourceStatus
from .behaviours import DEMO_NODES

#: The demo stays on this machine: discovery only over loopback.
DEMO_ENVIRONMENT = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}


class DemoNodes:
    """The demo nodes, each in a child process that ends when we close its stdin.

    ``start`` returns at once: the processes are started from a thread of their own
    (starting a process stalls the caller until it runs, a second and more each on a busy
    machine, and the caller is the app's event loop); ``wait_started`` waits for them."""

    def __init__(self, names: list[str] | None = None, *, domain: int | None = None) -> None:
        self.names = names or list(DEMO_NODES)
        self.processes: list[subprocess.Popen] = []
        #: Shown in the status line while the app runs the demo: its nodes, and the domain
        #: they run on (``ROS_DOMAIN_ID`` is set for them when ``domain`` is given).
        self.domain = domain
        where = f" on domain {domain}" if domain is not None else ""
        self.status = SourceStatus(path=f"demo: {plural(len(self.names), 'node')}{where}")
        self._lock = threading.Lock()
        self._stopping = False
        self._starter: threading.Thread | None = None

    def start(self) -> None:
        self._starter = threading.Thread(target=self._start_all, name="console-tui-demo", daemon=True)
        self._starter.start()

    def wait_started(self, timeout: float = 30.0) -> None:
        if self._starter is not None:
            self._starter.join(timeout)

    def _start_all(self) -> None:
        env = {**os.environ, **DEMO_ENVIRONMENT, "RCUTILS_LOGGING_USE_STDOUT": "0"}
        if self.domain is not None:
            env["ROS_DOMAIN_ID"] = str(self.domain)
        for name in self.names:
            with self._lock:
                if self._stopping:
                    return
                self.processes.append(
                    subprocess.Popen(
                        [sys.executable, "-m", "console_tui.demo.nodes", name],
                        stdin=subprocess.PIPE,
                        stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL,
                        env=env,
                    )
                )

    def stop(self, timeout: float = 0.8) -> None:
        """Close every node's stdin (each then shuts down cleanly), and kill those still
        running after ``timeout`` seconds in all."""
        with self._lock:
            self._stopping = True
            processes, self.processes = self.processes, []
        stop_children(processes, timeout)


def stop_children(processes: list[subprocess.Popen], timeout: float) -> None:
    """End demo processes that stop when their stdin closes: close every stdin, then wait
    for them, ``timeout`` seconds in all, and kill those still running."""
    for process in processes:
        close_stdin(process)
    deadline = time.monotonic() + timeout
    for process in processes:
        try:
            process.wait(max(deadline - time.monotonic(), 0.0))
        except subprocess.TimeoutExpired:
            process.kill()
    for process in processes:
        process.wait()


def close_stdin(process: subprocess.Popen) -> None:
    if process.stdin is not None:
        try:
            process.stdin.close()
        except OSError:
            pass
