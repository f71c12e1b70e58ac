"""Real ROS 1 for tests: a master on a port of the worker's own (roscore, or a bare rosmaster without the
rosout node), rospy nodes run by the system Python, roscpp nodes built from tests/nodes,
every process in its own group and every one of them stopped at the end."""

from __future__ import annotations

import hashlib
import os
import shutil
import signal
import socket
import subprocess
import time
import xmlrpc.client
from pathlib import Path

from support.rosproc import NODES, PATIENCE_S, NodeProcess, NodeProcesses, wait_until
from support.shares import range_of, taker

SYSTEM_PYTHON = "/usr/bin/python3"
ROSCPP_SOURCE = NODES / "roscpp_node.cpp"
#: The roscpp node logs through the logger ``ros.<this>`` (rosconsole's default name).
ROSCPP_PACKAGE = "console_tui_test"
ROSCPP_LOGGER = f"ros.{ROSCPP_PACKAGE}"
_ROSCPP_DEFINES = [f'-DROS_PACKAGE_NAME="{ROSCPP_PACKAGE}"']


def ros1_missing(*tools: str) -> str:
    """Why ROS 1 tests cannot run here (roscore, rosmaster, rosnode and ``tools``), or "" when they can."""
    for tool in ("roscore", "rosmaster", "rosnode", *tools):
        if shutil.which(tool) is None:
            return f"{tool} is not installed (apt-get install ros-core python3-rospy libroscpp-dev)"
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "import rospy"], capture_output=True)
    if probe.returncode != 0:
        return "rospy is not importable by /usr/bin/python3 (apt-get install python3-rospy)"
    return ""


def roscpp_missing() -> str:
    if shutil.which("g++") is None:
        return "g++ is not installed"
    if not Path("/usr/include/ros/ros.h").exists():
        return "roscpp headers are not installed (apt-get install libroscpp-dev)"
    return ""


#: ``CONSOLE_TUI_TEST_ROS1_PORTS=FIRST-LAST``: the ports the tests' ROS 1 masters (and their
#: ``serve``) listen on, a share for each xdist worker. The default lies below Linux's ephemeral ports (32768 and up):
#: a port the kernel hands out to any socket bound to port 0 (every ROS 1 node's XML-RPC
#: server) could be taken between a test's choice and roscore's bind, and the test would ask a
#: node's slave API for the master's ``getSystemState``.
PORTS_VARIABLE = "CONSOLE_TUI_TEST_ROS1_PORTS"
DEFAULT_PORTS = (21100, 22099)
_ports = taker(lambda: range_of(PORTS_VARIABLE, DEFAULT_PORTS, 1024, 65535, "21100-22099"))


def own_port() -> int:
    """A port for a test's server (a ROS 1 master, serve): this worker's next one that nothing listens on."""
    for port in _ports():
        with socket.socket() as sock:
            try:
                sock.bind(("127.0.0.1", port))
            except OSError:
                continue
            return port
    low, high = range_of(PORTS_VARIABLE, DEFAULT_PORTS, 1024, 65535, "21100-22099")
    raise RuntimeError(f"no free port for a ROS 1 master in {low}-{high} ({PORTS_VARIABLE})")


def ros1_environment(base: Path, port: int) -> dict[str, str]:
    """The environment for ROS 1 processes of one test: its master, loopback, logs under ``base``."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "VIRTUAL_ENV", "ROS_"))}
    env.update(
        ROS_MASTER_URI=f"http://127.0.0.1:{port}",
        ROS_IP="127.0.0.1",
        ROS_LOG_DIR=str(base / "log"),
        ROS_HOME=str(base / "home"),
        ROSCONSOLE_STDOUT_LINE_BUFFERED="1",
    )
    return env


def stop_group(process: subprocess.Popen, timeout: float = 10.0) -> None:
    """SIGINT to the process group it leads, then SIGKILL if needed; waits for it."""
    if process.poll() is not None:
        return
    try:
        os.killpg(process.pid, signal.SIGINT)
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        process.wait(5)
    except ProcessLookupError:
        pass


def kill_group(process: subprocess.Popen) -> None:
    """SIGKILL to the whole group: as a crash, nothing unregisters."""
    if process.poll() is None:
        try:
            os.killpg(process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        process.wait(5)


def master_call(uri: str, method: str, *args):
    proxy = xmlrpc.client.ServerProxy(uri)
    return getattr(proxy, method)("/test", *args)


class Ros1Master:
    """``roscore -p PORT`` (master, rosout node, /run_id), or with ``bare`` a ``rosmaster
    --core`` alone (no rosout node, no /rosout_agg). ``restart`` starts it again on the same port."""

    def __init__(self, base: Path, port: int, env: dict[str, str], *, bare: bool = False) -> None:
        self.base = base
        self.port = port
        self.env = env
        self.bare = bare
        self.uri = f"http://127.0.0.1:{port}"
        self.process: subprocess.Popen | None = None
        self.runs = 0

    def start(self, timeout: float = 30.0) -> None:
        self.runs += 1
        command = ["rosmaster", "--core", "-p", str(self.port)] if self.bare else ["roscore", "-p", str(self.port)]
        out = self.base / f"master-{self.runs}.out"
        self.process = subprocess.Popen(
            command, env=self.env, start_new_session=True, stdout=open(out, "wb"), stderr=subprocess.STDOUT
        )
        ready = wait_until(self._ready, timeout, interval=0.1)
        assert ready, f"{command} did not come up: {out.read_text()[-2000:]}"

    def _ready(self) -> bool:
        try:
            state = master_call(self.uri, "getSystemState")
        except OSError:
            return False
        except xmlrpc.client.Fault as fault:  # not a master: another server has the port
            raise AssertionError(f"{self.uri} answers, but is no ROS 1 master: {fault}") from None
        if self.bare:
            return True
        publishers = dict((topic, nodes) for topic, nodes in state[2][0])
        return "/rosout" in publishers.get("/rosout_agg", [])

    def stop(self) -> None:
        if self.process is not None:
            stop_group(self.process)

    def kill(self) -> None:
        if self.process is not None:
            kill_group(self.process)

    def restart(self) -> None:
        self.stop()
        self.start()

    def publishers(self, topic: str) -> list[str]:
        return self._state(0).get(topic, [])

    def subscribers(self, topic: str) -> list[str]:
        return self._state(1).get(topic, [])

    def _state(self, part: int) -> dict[str, list[str]]:
        return {name: nodes for name, nodes in master_call(self.uri, "getSystemState")[2][part]}

    def node_pid(self, node: str) -> int | None:
        """The pid of a registered node, or None when it does not answer."""
        try:
            uri = master_call(self.uri, "lookupNode", node)[2]
            return int(master_call(uri, "getPid")[2])
        except (OSError, ValueError, xmlrpc.client.Error):
            return None


class Ros1Nodes(NodeProcesses):
    """Node processes of one test: rospy scripts (system Python) and the roscpp node."""

    def __init__(self, env: dict[str, str], roscpp_binary: Path | None = None) -> None:
        super().__init__(env)
        self.roscpp_binary = roscpp_binary

    def rospy(self, script: str, *args: str) -> NodeProcess:
        return self.add(NodeProcess(script, *args, env=self.env, python=SYSTEM_PYTHON))

    def roscpp(self, *args: str) -> NodeProcess:
        assert self.roscpp_binary is not None, "use the roscpp_binary fixture"
        return self.add(NodeProcess("", *args, env=self.env, command=[str(self.roscpp_binary)]))


def build_roscpp_node(cache: Path) -> Path:
    """tests/nodes/roscpp_node.cpp built with g++ (once per version of the source)."""
    source = ROSCPP_SOURCE.read_bytes()
    digest = hashlib.sha256(source + " ".join(_ROSCPP_DEFINES).encode()).hexdigest()[:16]
    binary = cache / f"roscpp_node-{digest}"
    if binary.exists():
        return binary
    cache.mkdir(parents=True, exist_ok=True)
    partial = cache / f".roscpp_node-{digest}-{os.getpid()}"
    flags = _pkg_config("roscpp rosconsole roscpp_serialization rostime")
    command = [
        "g++",
        "-O2",
        "-std=c++17",
        *_ROSCPP_DEFINES,
        "-o",
        str(partial),
        str(ROSCPP_SOURCE),
        *flags,
        "-lpthread",
    ]
    result = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, f"{' '.join(command)}\n{result.stderr[-4000:]}"
    os.replace(partial, binary)
    return binary


def _pkg_config(packages: str) -> list[str]:
    result = subprocess.run(["pkg-config", "--cflags", "--libs", *packages.split()], capture_output=True, text=True)
    if result.returncode == 0:
        return result.stdout.split()
    return [
        "-I/usr/include",
        "-lroscpp",
        "-lrosconsole",
        "-lroscpp_serialization",
        "-lrostime",
        "-lxmlrpcpp",
        "-lcpp_common",
    ]


def wait_for(condition, timeout: float = PATIENCE_S, what: str = "the condition") -> None:
    assert wait_until(condition, timeout), f"timed out waiting for {what}"


def pause(seconds: float) -> None:
    time.sleep(seconds)
