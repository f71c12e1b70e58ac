"""What console-tui says when rclpy cannot be imported: the import that failed, and the fix."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from console_tui.ros.ros2.rclpy_loader import import_failure_text

REPO = Path(__file__).resolve().parents[2]


def missing(name: str) -> ModuleNotFoundError:
    return ModuleNotFoundError(f"No module named '{name}'", name=name)


def test_no_rclpy_at_all_says_how_to_get_it():
    text = import_failure_text(missing("rclpy"), None, isolated_venv=True)
    assert text.startswith("ROS 2 (rclpy) is not available in this Python (")
    assert "source /opt/ros/$ROS_DISTRO/setup.bash" in text
    assert "python3 -m venv --system-site-packages .venv" in text
    assert "pip install 'console-tui[ros]'" in text


def test_a_missing_dependency_is_named_not_rclpy():
    text = import_failure_text(missing("yaml"), "/opt/ros/jazzy/lib/python3.12/site-packages/rclpy", True)
    assert text.startswith("rclpy was found (/opt/ros/jazzy/lib/python3.12/site-packages/rclpy) but could not be")
    assert "it imports the Python module 'yaml', which this Python (" in text
    assert "made without --system-site-packages" in text
    assert text.endswith("python3 -m venv --system-site-packages .venv")
    assert "not available" not in text


def test_outside_an_isolated_venv_the_missing_module_is_to_install():
    text = import_failure_text(missing("numpy"), "/opt/ros/kilted/rclpy", isolated_venv=False)
    assert "'numpy'" in text and "python3-numpy package, or pip install numpy" in text
    assert "--system-site-packages" not in text


def test_another_import_error_is_shown_with_what_to_check():
    error = ImportError("librcl.so: cannot open shared object file: No such file or directory")
    text = import_failure_text(error, "/opt/ros/kilted/rclpy", isolated_venv=False)
    assert "could not be imported: ImportError: librcl.so: cannot open shared object file" in text
    assert "source /opt/ros/$ROS_DISTRO/setup.bash" in text and "built for this Python" in text


def test_a_real_import_of_an_rclpy_that_lacks_a_module(tmp_path):
    # An rclpy of our own on PYTHONPATH, as a sourced ROS puts one there, that imports a
    # module this Python does not have.
    (tmp_path / "rclpy").mkdir()
    (tmp_path / "rclpy" / "__init__.py").write_text("import console_tui_absent_dependency\n")
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), str(REPO)])}
    result = subprocess.run(
        [sys.executable, "-m", "console_tui", "loggers", "list", "--wait", "0"],
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert result.returncode == 2 and result.stdout == ""  # "ROS is not available": 2 in every command
    assert f"rclpy was found ({tmp_path / 'rclpy'}) but could not be imported" in result.stderr
    assert "it imports the Python module 'console_tui_absent_dependency'" in result.stderr
