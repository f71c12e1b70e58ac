"""Starting and stopping the demo node processes."""

from __future__ import annotations

import os
import subprocess
import sys

from ..model.text import plural
from ..sources.status import SourceStatus
from .behaviours import DEMO_NODES

#: The demo stays on this machine: discovery only over loopback.
DEMO_ENVIRONMENT = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}


class DemoNodes:
    """The demo nodes, each in a child process that ends when we close its stdin."""

    def __init__(self, names: list[str] | None = None) -> None:
        self.names = names or list(DEMO_NODES)
        self.processes: list[subprocess.Popen] = []
        #: Shown in the status line while the app runs the demo.
        self.status = SourceStatus(path=f"demo: {plural(len(self.names), 'node')}")

    def start(self) -> None:
        env = {**os.environ, **DEMO_ENVIRONMENT, "RCUTILS_LOGGING_USE_STDOUT": "0"}
        for name in self.names:
            self.processes.append(
                subprocess.Popen(
                    [sys.executable, "-m", "console_tui.demo.nodes", name],
                    stdin=subprocess.PIPE,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                    env=env,
                )
            )

    def stop(self, timeout: float = 3.0) -> None:
        processes, self.processes = self.processes, []
        stop_children(processes, timeout)


def stop_children(processes: list[subprocess.Popen], timeout: float) -> None:
    """End demo processes that stop when their stdin closes: close every stdin, then wait for
    each (killing one that takes longer than ``timeout``)."""
    for process in processes:
        close_stdin(process)
    for process in processes:
        try:
            process.wait(timeout)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(timeout)


def close_stdin(process: subprocess.Popen) -> None:
    if process.stdin is not None:
        try:
            process.stdin.close()
        except OSError:
            pass
