"""Shared fixtures: ROS environments that stay on loopback and never cross between tests."""

from __future__ import annotations

import itertools
import os
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))

from rosproc import ros_available  # noqa: E402

_counter = itertools.count()


def _worker_number() -> int:
    worker = os.environ.get("PYTEST_XDIST_WORKER", "gw0")
    digits = "".join(ch for ch in worker if ch.isdigit())
    return int(digits or 0)


def next_domain_id() -> int:
    """A ROS_DOMAIN_ID no other test of this run uses at the same time (1..100)."""
    return 1 + (_worker_number() % 4) * 25 + next(_counter) % 25


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
    from rosproc import NodeProcesses

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
    from console_tui.sources.ros2.runtime import RosRuntime

    runtime = RosRuntime()
    runtime.create_node("test_keeper")
    yield runtime
    runtime.shutdown()
