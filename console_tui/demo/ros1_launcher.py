"""The ROS 1 demo: a roscore of its own on a free port, and rospy demo nodes, all stopped at exit.

The demo never touches a master the user has running: it starts ``roscore`` on a free
loopback port, points this process at it (``ROS_MASTER_URI``, ``ROS_IP=127.0.0.1``, set
before the ROS 1 source and logger control are made), keeps roscore's logs in a temporary
folder removed at exit, and runs each demo node with the system Python, where rospy imports.
Starting happens on a thread of its own (roscore takes a second or two to come up), so the
first frame never waits; the status line says how far it got or what went wrong.
"""

from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from ..ros.ros1.master import Ros1CallError, probe_master, xmlrpc_call
from ..sources.status import SourceStatus
from .behaviours import DEMO_NODES
from .launcher import close_stdin, stop_children

#: Debian's rospy (and a sourced Noetic's) imports in the system Python.
SYSTEM_PYTHON = "/usr/bin/python3"
NODE_SCRIPT = Path(__file__).with_name("ros1_nodes.py")
MASTER_WAIT_S = 30.0
#: roscore runs under this watchdog, which stops it when its stdin closes: when the console
#: exits, or dies, so that no roscore outlives it. Then it removes the demo's folder (its
#: first argument, made by the console with ``mkdtemp``), which a killed console cannot.
WATCHDOG = """
import os, shutil, signal, subprocess, sys, time
folder = sys.argv[1]
core = subprocess.Popen(sys.argv[2:], stdin=subprocess.DEVNULL)
try:
    sys.stdin.read()
finally:
    core.send_signal(signal.SIGINT)
    try:
        core.wait(10)
    except subprocess.TimeoutExpired:
        core.kill()
    for _ in range(20):  # the demo's nodes, ending too, may still be writing their logs there
        shutil.rmtree(folder, ignore_errors=True)
        if not os.path.exists(folder):
            break
        time.sleep(0.25)
"""
HOW_TO_GET_ROS1 = (
    "the ROS 1 demo needs roscore and rospy: apt-get install ros-core python3-rospy (Debian), "
    "or source /opt/ros/noetic/setup.bash"
)


class Ros1DemoUnavailable(RuntimeError):
    """roscore is not installed; the text says how to get it."""


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def _python() -> str:
    return SYSTEM_PYTHON if os.path.exists(SYSTEM_PYTHON) else (shutil.which("python3") or "python3")


class Ros1Demo:
    """roscore on a free port and the demo nodes; ``start`` (non-blocking), ``stop``, ``status``.

    Made before the ROS 1 source: it sets ``ROS_MASTER_URI`` and ``ROS_IP`` in this process.
    """

    def __init__(self, names: list[str] | None = None) -> None:
        if shutil.which("roscore") is None:
            raise Ros1DemoUnavailable(f"roscore is not installed: {HOW_TO_GET_ROS1}")
        self.names = names or list(DEMO_NODES)
        self.port = _free_port()
        self.master_uri = f"http://127.0.0.1:{self.port}"
        os.environ["ROS_MASTER_URI"] = self.master_uri
        os.environ["ROS_IP"] = "127.0.0.1"
        os.environ.pop("ROS_HOSTNAME", None)
        self._folder = tempfile.mkdtemp(prefix="console-tui-ros1-demo-")
        self.env = {k: v for k, v in os.environ.items() if not k.startswith(("VIRTUAL_ENV", "PYTHONHOME"))}
        self.env.update(ROS_LOG_DIR=os.path.join(self._folder, "log"), ROS_HOME=os.path.join(self._folder, "home"))
        self.roscore: subprocess.Popen | None = None
        self.processes: list[subprocess.Popen] = []
        self.status = SourceStatus(path=f"demo: roscore on port {self.port}, {len(self.names)} rospy nodes")
        self._lock = threading.Lock()
        self._stopped = False
        self._thread: threading.Thread | None = None

    def start(self) -> None:
        with self._lock:
            self.roscore = subprocess.Popen(
                [sys.executable, "-c", WATCHDOG, self._folder, "roscore", "-p", str(self.port)],
                env=self.env,
                stdin=subprocess.PIPE,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                start_new_session=True,  # its own process group: stopped whole, children too
            )
        self._thread = threading.Thread(target=self._start_nodes, name="console-tui-ros1-demo", daemon=True)
        self._thread.start()

    def _start_nodes(self) -> None:
        deadline = time.monotonic() + MASTER_WAIT_S
        while not probe_master(self.master_uri, timeout=0.5):
            if self._stopped:
                return
            if time.monotonic() > deadline or (self.roscore is not None and self.roscore.poll() is not None):
                self._problem(f"demo: roscore did not start on port {self.port}")
                return
            time.sleep(0.1)
        python = _python()
        probe = subprocess.run([python, "-c", "import rospy"], env=self.env, capture_output=True)
        if probe.returncode != 0:
            self._problem(f"demo: rospy does not import in {python}: {HOW_TO_GET_ROS1}")
            return
        with self._lock:
            for name in self.names:
                if self._stopped:
                    return
                self.processes.append(
                    subprocess.Popen(
                        [python, str(NODE_SCRIPT), name],
                        env=self.env,
                        stdin=subprocess.PIPE,
                        stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL,
                    )
                )

    def _problem(self, text: str) -> None:
        self.status = SourceStatus(path=self.status.path, problem=text)

    def stop(self, timeout: float = 5.0) -> None:
        with self._lock:
            self._stopped = True
            processes, self.processes = self.processes, []
        leftovers: list[int] = []
        if self.roscore is not None:  # roscore and the nodes stop at once: quitting waits for the slower
            leftovers = self._master_processes()
            close_stdin(self.roscore)
            self._signal_ours(leftovers, signal.SIGINT)  # rosmaster and rosout too, not one after the other
        stop_children(processes, timeout)
        if self.roscore is not None:
            try:
                self.roscore.wait(timeout + 5.0)
            except subprocess.TimeoutExpired:
                pass
            try:  # whatever is left of its group (the watchdog, roslaunch, rosmaster, rosout)
                os.killpg(self.roscore.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            self.roscore.wait(timeout)
            self._signal_ours(leftovers, signal.SIGKILL)  # roslaunch gives them sessions of their own
        shutil.rmtree(self._folder, ignore_errors=True)

    def _signal_ours(self, pids: list[int], number: signal.Signals) -> None:
        """Send ``number`` to those of ``pids`` still this demo's (rosmaster, rosout)."""
        for pid in pids:
            if _is_ours(pid, str(self.port)) or _is_ours(pid, self._folder):
                try:
                    os.kill(pid, number)
                except (ProcessLookupError, PermissionError):
                    pass

    def _master_processes(self) -> list[int]:
        """The pids of this demo's rosmaster and rosout (they are not in roscore's process group)."""
        pids = []
        try:
            pids.append(int(xmlrpc_call(self.master_uri, "getPid", "/console_tui_demo", timeout=1.0)))
            rosout = xmlrpc_call(self.master_uri, "lookupNode", "/console_tui_demo", "/rosout", timeout=1.0)
            pids.append(int(xmlrpc_call(str(rosout), "getPid", "/console_tui_demo", timeout=1.0)))
        except (Ros1CallError, ValueError, TypeError):
            pass
        return pids


def _is_ours(pid: int, text: str) -> bool:
    """Whether process ``pid`` is still one of ours: its command line mentions ``text``."""
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as cmdline:
            return text.encode() in cmdline.read()
    except OSError:
        return False
