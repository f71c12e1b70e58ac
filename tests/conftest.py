"""Shared fixtures: ROS environments that stay on loopback and never cross between tests."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from support.rosproc import ros_available
from support.shares import range_of, taker

#: ``CONSOLE_TUI_TEST_DOMAINS=FIRST-LAST`` picks the ROS_DOMAIN_IDs the tests may use (both
#: included); the default keeps them in 1-100. On a shared network, pick a range nobody else
#: uses: the tests' nodes talk only over loopback, but a domain is a domain.
DOMAINS_VARIABLE = "CONSOLE_TUI_TEST_DOMAINS"
DEFAULT_DOMAINS = (1, 100)


def domain_range() -> tuple[int, int]:
    """The first and last ROS_DOMAIN_ID the tests may use."""
    return range_of(DOMAINS_VARIABLE, DEFAULT_DOMAINS, 0, 232, "120-160")


_domains = taker(domain_range)


def next_domain_id() -> int:
    """A ROS_DOMAIN_ID no other test of this run uses at the same time: each xdist worker
    takes turns through a share of the range of its own."""
    return next(_domains())


@pytest.fixture(autouse=True)
def own_config_folder(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> Path:
    """Each test reads and writes settings (keys.toml), state (the last rules, the query
    history) and the history on disk in folders of its own, never the developer's."""
    folder = tmp_path / "config"
    monkeypatch.setenv("XDG_CONFIG_HOME", str(folder))
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))
    monkeypatch.setenv("CONSOLE_TUI_HISTORY_DIR", str(tmp_path / "history"))
    return folder


@pytest.fixture(autouse=True)
def app_ready_for_the_test(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> None:
    """``ConsoleApp.run_test`` gives the test its pilot once the panes hidden at start are
    mounted (right after the first frame): a person's keys wait for them (``focus.KeyGate``),
    and a test that calls into a pane waits the same way. Tests marked ``first_frame`` get
    the app as the first frame shows it, the panes not mounted yet."""
    if "console_tui.ui.app" not in sys.modules or request.node.get_closest_marker("first_frame"):
        return  # tests without the UI do not import Textual for it
    from support.ui import run_test_when_ready

    monkeypatch.setattr(sys.modules["console_tui.ui.app"].ConsoleApp, "run_test", run_test_when_ready)


@pytest.fixture
def ros_env(monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """A ROS 2 environment of its own for one test: its own domain, loopback only.

    Sets the variables in this process too (for an app run in-process) and returns the
    environment to start node processes with. Fast DDS is held to UDP so that killed
    processes leave no shared-memory segments behind.
    """
    if not ros_available():
        pytest.skip("rclpy is not installed (pip install -e '.[ros]')")
    values = {
        "ROS_DOMAIN_ID": str(next_domain_id()),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "FASTDDS_BUILTIN_TRANSPORTS": "UDPv4",
        "RCUTILS_COLORIZED_OUTPUT": "0",
    }
    for key, value in values.items():
        monkeypatch.setenv(key, value)
    monkeypatch.delenv("ROS_LOCALHOST_ONLY", raising=False)
    return {**os.environ, **values}


@pytest.fixture
def nodes(ros_env):
    """Start node scripts from tests/nodes in the test's ROS environment."""
    from support.rosproc import NodeProcesses

    processes = NodeProcesses(ros_env)
    yield processes
    processes.stop_all()


@pytest.fixture
def ros_runtime(ros_env):
    """A ``RosRuntime`` in the test's ROS environment, shut down at the end.

    It keeps one node of its own for the whole test: rmw starts discovery over when a
    context's last node is destroyed, and parts that come and go (a logger control, a
    command run in-process) would otherwise each wait for discovery again.
    """
    from console_tui.ros.ros2.runtime import RosRuntime

    runtime = RosRuntime()
    runtime.create_node("test_keeper")
    yield runtime
    runtime.shutdown()


# -- ROS 1 -----------------------------------------------------------------------------------


@pytest.fixture
def ros1_env(tmp_path, monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    """A ROS 1 environment of its own for one test: a port of its own for its master, loopback,
    logs under the test's tmp folder. Set in this process too (for sources run in-process)."""
    from support.ros1 import own_port, ros1_environment, ros1_missing

    reason = ros1_missing()
    if reason:
        pytest.skip(reason)
    env = ros1_environment(tmp_path, own_port())
    for key in [k for k in os.environ if k.startswith("ROS_")]:
        monkeypatch.delenv(key)
    for key, value in env.items():
        if key.startswith("ROS"):
            monkeypatch.setenv(key, value)
    return env


def _master(tmp_path, ros1_env, *, bare: bool):
    from support.ros1 import Ros1Master

    port = int(ros1_env["ROS_MASTER_URI"].rsplit(":", 1)[1])
    master = Ros1Master(tmp_path, port, ros1_env, bare=bare)
    master.start()
    return master


@pytest.fixture
def roscore(tmp_path, ros1_env):
    """``roscore`` on the test's port (master, rosout node, /rosout_agg), stopped at the end."""
    master = _master(tmp_path, ros1_env, bare=False)
    yield master
    master.stop()


@pytest.fixture
def bare_master(tmp_path, ros1_env):
    """``rosmaster --core`` alone on the test's port: no rosout node, no /rosout_agg."""
    master = _master(tmp_path, ros1_env, bare=True)
    yield master
    master.stop()


@pytest.fixture(scope="session")
def roscpp_binary(request, tmp_path_factory):
    """tests/nodes/roscpp_node.cpp, built once (kept in pytest's cache between runs)."""
    from support.ros1 import build_roscpp_node, ros1_missing, roscpp_missing

    reason = ros1_missing() or roscpp_missing()
    if reason:
        pytest.skip(reason)
    return build_roscpp_node(request.config.cache.mkdir("roscpp_node"))


@pytest.fixture
def ros1_nodes(ros1_env, request):
    """Start rospy scripts from tests/nodes (system Python) and the roscpp node; all stopped at the end."""
    from support.ros1 import Ros1Nodes

    binary = request.getfixturevalue("roscpp_binary") if "roscpp_binary" in request.fixturenames else None
    nodes = Ros1Nodes(ros1_env, binary)
    yield nodes
    nodes.stop_all()


def pytest_terminal_summary(terminalreporter) -> None:
    """Say, after the counts, a tier skipped for want of what it runs against (a ClickHouse
    server: ``CLICKHOUSE_URL``), so that a green run does not read as having tested it."""
    said = set()
    for report in terminalreporter.stats.get("skipped", []):
        reason = str(report.longrepr[-1]) if isinstance(report.longrepr, tuple) else ""
        if "CLICKHOUSE_URL" in reason and reason not in said:
            said.add(reason)
            terminalreporter.write_line(f"not tested: {reason.removeprefix('Skipped: ')}", yellow=True)
