"""Importing rclpy, with a message that says what failed and how to fix it."""

from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path
from types import ModuleType

HOW_TO_GET_ROS2 = (
    "  - On a robot: source your ROS 2 install first, and use a virtual environment that sees\n"
    "    the system's packages (rclpy imports the system's yaml and numpy):\n"
    "      source /opt/ros/$ROS_DISTRO/setup.bash\n"
    "      python3 -m venv --system-site-packages .venv && .venv/bin/pip install -e .   # in a clone\n"
    "  - Anywhere else: install the optional extra with the rclpy wheels:\n"
    "      pip install 'console-tui[ros]'\n"
    "  - Or without ROS: open log files and recordings (console-tui FILE ...)."
)


class RosUnavailable(RuntimeError):
    """rclpy cannot be imported; the message says what failed and how to fix it."""


def load_rclpy() -> ModuleType:
    """Import and return ``rclpy``, or raise ``RosUnavailable`` saying what failed."""
    try:
        rclpy = importlib.import_module("rclpy")
        importlib.import_module("rcl_interfaces.msg")
    except Exception as error:  # ImportError, or a broken install raising anything
        raise RosUnavailable(import_failure_text(error, rclpy_location(), _venv_without_system_packages())) from None
    return rclpy


def require_rclpy() -> None:
    """``RosUnavailable`` when this Python finds no rclpy at all: the check ``load_rclpy`` makes
    first, without the cost of importing it."""
    if rclpy_location() is None:
        raise RosUnavailable(import_failure_text(ModuleNotFoundError("rclpy"), None, False))


def import_failure_text(error: BaseException, rclpy_location: str | None, isolated_venv: bool) -> str:
    """What to tell a person whose ``import rclpy`` raised ``error``.

    ``rclpy_location``: where this Python finds rclpy, None when it finds none.
    ``isolated_venv``: this Python is a virtual environment made without
    ``--system-site-packages``.
    """
    python = f"this Python ({sys.executable}, {sys.version_info.major}.{sys.version_info.minor})"
    if rclpy_location is None:
        return f"ROS 2 (rclpy) is not available in {python}.\n{HOW_TO_GET_ROS2}"
    found = f"rclpy was found ({rclpy_location}) but could not be imported"
    missing = getattr(error, "name", None) if isinstance(error, ModuleNotFoundError) else None
    if missing and not missing.startswith(("rclpy", "rcl_interfaces")):
        text = f"{found}: it imports the Python module '{missing}', which {python} cannot import."
        if isolated_venv:
            return (
                f"{text}\nThis virtual environment was made without --system-site-packages, so the system's "
                f"packages, where a ROS install's Python modules ({missing}, yaml, numpy ...) come from, are "
                f"out of its reach. Make it again with them:\n"
                f"  python3 -m venv --system-site-packages .venv"
            )
        return f"{text}\nInstall it: your system's python3-{missing} package, or pip install {missing}."
    return (
        f"{found}: {type(error).__name__}: {error}\n"
        f"Is the ROS install sourced in this shell (source /opt/ros/$ROS_DISTRO/setup.bash), "
        f"and was it built for {python}?"
    )


def rclpy_location() -> str | None:
    """Where this Python finds rclpy (without importing it), None when it finds none."""
    try:
        spec = importlib.util.find_spec("rclpy")
    except Exception:
        return None
    if spec is None:
        return None
    places = list(spec.submodule_search_locations or []) or [spec.origin or "?"]
    return str(places[0])


def _venv_without_system_packages() -> bool:
    if sys.prefix == sys.base_prefix:
        return False
    try:
        config = (Path(sys.prefix) / "pyvenv.cfg").read_text()
    except OSError:
        return False
    for line in config.splitlines():
        key, _, value = line.partition("=")
        if key.strip() == "include-system-site-packages":
            return value.strip().lower() != "true"
    return True
