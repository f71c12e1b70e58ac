"""A robot's ROS 2 set-up, imitated from the rclpy wheels installed here: a ROS install prefix
(as /opt/ros/DISTRO: lib/, share/, lib/pythonX.Y/site-packages holding only ROS's packages),
the environment its setup.bash gives, and the system Python with its own packages."""

from __future__ import annotations

import importlib.metadata
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SYSTEM_PYTHON = Path("/usr/bin/python3")
#: What a ROS install's rclpy imports from the system (Debian/Ubuntu packages python3-*).
SYSTEM_MODULES = ("yaml", "numpy", "typing_extensions")
#: Installed with ROS's Python code, but not ROS: a robot has them from the system.
_NOT_ROS = {"ros-wheels-bootstrapper"}


def ros_prefix(into: Path) -> Path:
    """Build the prefix from the installed ROS wheels (symbolic links); returns it."""
    venv = Path(sys.prefix)
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = into / "lib" / version / "site-packages"
    site.mkdir(parents=True)
    for entry in (venv / "lib").iterdir():
        if not entry.name.startswith("python"):
            (into / "lib" / entry.name).symlink_to(entry)
    (into / "share").symlink_to(venv / "share")
    installed = Path(str(importlib.metadata.distribution("ros-rclpy").locate_file("")))
    tops: set[str] = set()
    for dist in importlib.metadata.distributions():
        name = dist.metadata["Name"].lower().replace("_", "-")
        if name.startswith("ros-") and name not in _NOT_ROS:
            tops.update(Path(str(f)).parts[0] for f in dist.files or () if Path(str(f)).parts[0] != "..")
    for top in tops:
        if (installed / top).exists():
            (site / top).symlink_to(installed / top)
    return into


def sourced_environment(prefix: Path, base: dict[str, str]) -> dict[str, str]:
    """``base`` as ``source PREFIX/setup.bash`` would leave it, with console-tui's code on
    PYTHONPATH (as ``pip install -e .`` would make it importable) and nothing of the test venv."""
    site = next((prefix / "lib").glob("python*/site-packages"))
    libraries = [prefix / "lib", *sorted(site.glob("ros_*.libs"))]
    env = {key: value for key, value in base.items() if key not in ("VIRTUAL_ENV", "PYTHONHOME")}
    env.pop("_ROS_WHEELS_BOOTSTRAP_COMPLETE", None)
    env.update(
        PYTHONPATH=os.pathsep.join([str(site), str(REPO)]),
        LD_LIBRARY_PATH=os.pathsep.join(str(path) for path in libraries),
        AMENT_PREFIX_PATH=str(prefix),
    )
    return env


def system_python_problem() -> str:
    """Why the system Python cannot stand in for a robot's, or ""."""
    if not SYSTEM_PYTHON.exists():
        return f"no {SYSTEM_PYTHON}"
    probe = subprocess.run(
        [str(SYSTEM_PYTHON), "-c", "import sys; print(f'{sys.version_info[0]}.{sys.version_info[1]}')"],
        capture_output=True,
        text=True,
    )
    mine = f"{sys.version_info.major}.{sys.version_info.minor}"
    if probe.stdout.strip() != mine:
        return f"{SYSTEM_PYTHON} is Python {probe.stdout.strip()}, the ROS wheels here are for {mine}"
    return ""


def system_modules_missing() -> list[str]:
    """The modules of ``SYSTEM_MODULES`` the system Python cannot import."""
    return [
        module
        for module in SYSTEM_MODULES
        if subprocess.run([str(SYSTEM_PYTHON), "-c", f"import {module}"], capture_output=True).returncode
    ]


def make_venv(path: Path, *, system_site_packages: bool) -> Path:
    """A virtual environment of the system Python; returns its python."""
    command = [str(SYSTEM_PYTHON), "-m", "venv", "--without-pip", str(path)]
    if system_site_packages:
        command.insert(3, "--system-site-packages")
    subprocess.run(command, check=True, capture_output=True)
    return path / "bin" / "python"
