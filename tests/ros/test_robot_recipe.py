"""The README's robot recipe, as far as this machine can imitate a robot: the system Python, a
ROS install's prefix on PYTHONPATH (built from the rclpy wheels installed here), and a virtual
environment made with or without ``--system-site-packages``."""

from __future__ import annotations

import re
import subprocess

import pytest

from support.robot import make_venv, ros_prefix, sourced_environment, system_modules_missing, system_python_problem

pytestmark = pytest.mark.ros2


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    problem = system_python_problem()
    if problem:
        pytest.skip(f"cannot imitate a robot here: {problem}")
    return ros_prefix(tmp_path_factory.mktemp("opt_ros") / "distro")


def console_tui(python, env, *args):
    return subprocess.run(
        [str(python), "-m", "console_tui", *args], env=env, capture_output=True, text=True, timeout=60
    )


def test_a_venv_without_the_system_packages_is_told_what_import_failed(prefix, tmp_path, ros_env):
    python = make_venv(tmp_path / "venv", system_site_packages=False)
    result = console_tui(python, sourced_environment(prefix, ros_env), "loggers", "list", "--wait", "0")
    assert result.returncode == 2 and result.stdout == ""  # ROS not available: 2 for every command
    site = next((prefix / "lib").glob("python*/site-packages"))
    assert f"rclpy was found ({site / 'rclpy'}) but could not be imported" in result.stderr
    assert re.search(r"it imports the Python module '(yaml|numpy|typing_extensions)'", result.stderr)
    assert "python3 -m venv --system-site-packages .venv" in result.stderr
    assert "not available" not in result.stderr


def test_the_recipe_venv_reaches_a_node_through_the_system_rclpy(prefix, tmp_path, ros_env, nodes):
    missing = system_modules_missing()
    if missing:
        pytest.skip(
            f"the system Python lacks {', '.join(missing)} (apt-get install python3-yaml python3-numpy "
            "python3-typing-extensions)"
        )
    nodes.start("talker.py", "--name", "on_robot").expect("ready")
    python = make_venv(tmp_path / "venv", system_site_packages=True)
    env = sourced_environment(prefix, ros_env)
    located = subprocess.run(
        [str(python), "-c", "import rclpy; print(rclpy.__file__)"], env=env, capture_output=True, text=True
    )
    assert located.stdout.startswith(str(prefix)), located.stderr
    result = console_tui(python, env, "loggers", "get", "on_robot", "--wait", "20")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["on_robot\tinherited\tINFO", '""\tINFO\tINFO']
