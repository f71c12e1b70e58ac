"""One rclpy context for the whole app, with its own nodes, started and stopped cleanly."""

from __future__ import annotations

import os
import re
import threading
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .rclpy_loader import RosUnavailable, load_rclpy, rclpy_location, require_rclpy

FASTDDS_PROFILE = Path(__file__).with_name("fastdds_reader_profile.xml")
_PROFILE_VARIABLES = ("FASTDDS_DEFAULT_PROFILES_FILE", "FASTRTPS_DEFAULT_PROFILES_FILE")
_FAST_DDS_2_DISTROS = frozenset({"foxy", "galactic", "humble", "iron", "jazzy"})


def reader_profile_environment(
    environ: Mapping[str, str], cwd: str | os.PathLike[str] = ".", *, fast_dds_2: bool | None = None
) -> dict[str, str]:
    """What to add to the environment so that this process's Fast DDS readers can hold
    more unread messages (see fastdds_reader_profile.xml): nothing under another RMW, or
    when the user has a Fast DDS profiles file of their own (named by a variable, or the
    DEFAULT_FASTDDS_PROFILES.xml that Fast DDS reads from the working directory).

    Fast DDS 3 (Kilted and later) reads ``FASTDDS_DEFAULT_PROFILES_FILE`` and warns about
    the old name; Fast DDS 2 (Humble, Iron, Jazzy) reads only ``FASTRTPS_DEFAULT_PROFILES_FILE``:
    both are set there (``fast_dds_2``: None finds out, see ``uses_fast_dds_2``)."""
    rmw = environ.get("RMW_IMPLEMENTATION", "rmw_fastrtps_cpp")
    if not rmw.startswith("rmw_fastrtps"):
        return {}
    if any(environ.get(name) for name in _PROFILE_VARIABLES):
        return {}
    if any((Path(cwd) / name).exists() for name in ("DEFAULT_FASTDDS_PROFILES.xml", "DEFAULT_FASTRTPS_PROFILES.xml")):
        return {}
    if fast_dds_2 is None:
        fast_dds_2 = uses_fast_dds_2(environ)
    return dict.fromkeys(_PROFILE_VARIABLES if fast_dds_2 else _PROFILE_VARIABLES[:1], str(FASTDDS_PROFILE))


def uses_fast_dds_2(environ: Mapping[str, str]) -> bool:
    """Whether this ROS 2 comes with Fast DDS 2: a sourced Humble, Iron or Jazzy, or an
    rclpy older than Kilted's (9.x)."""
    distro = environ.get("ROS_DISTRO", "")
    if distro:
        return distro in _FAST_DDS_2_DISTROS
    major = _rclpy_major()
    return major is not None and major < 9


def _rclpy_major() -> int | None:
    """rclpy's major version, from the name of its metadata beside it (``rclpy-9.1.2.dist-info``,
    ``rclpy-9.1.2-py3.11.egg-info``), else from ``importlib.metadata``; None when unknown.
    (Importing ``importlib.metadata`` costs tens of ms at start, before the first frame.)"""
    location = rclpy_location()
    if location is not None and Path(location).is_dir():
        for info in Path(location).parent.glob("rclpy-*-info"):
            found = re.match(r"rclpy-(\d+)\.", info.name)
            if found:
                return int(found.group(1))
    import importlib.metadata

    try:
        return int(importlib.metadata.version("rclpy").split(".")[0])
    except (importlib.metadata.PackageNotFoundError, ValueError):
        return None


#: The highest DDS domain: above it the ports a participant needs pass 65535 (Fast DDS ends
#: the whole process there, with exit status 1 and no word to Python).
MAX_DOMAIN_ID = 232


def check_domain_id(environ: Mapping[str, str]) -> None:
    """``RosUnavailable`` for a ``ROS_DOMAIN_ID`` no DDS can use (rcl itself refuses text)."""
    value = environ.get("ROS_DOMAIN_ID", "").strip()
    if value.isdigit() and int(value) > MAX_DOMAIN_ID:
        raise RosUnavailable(
            f"ROS_DOMAIN_ID={value} is out of range: DDS domains go from 0 to {MAX_DOMAIN_ID} "
            "(ROS 2 advises 0 to 101). Set another and start again."
        )


class RosRuntime:
    """Owns an rclpy ``Context`` (not the global one) and the nodes made on it.

    rclpy's signal handlers are not installed: the terminal app handles Ctrl+C itself.
    ``shutdown`` is idempotent and safe to call from any thread.
    """

    def __init__(self, args: list[str] | None = None, *, domain_id: int | None = None, deferred: bool = False) -> None:
        """``domain_id``: the DDS domain of this context (a fleet's robot), else ``ROS_DOMAIN_ID``'s.
        ``deferred``: rclpy is imported and the context made at the first use (``create_node``,
        ``context``), from whichever thread; now only what needs no rclpy is checked (the domain,
        that there is an rclpy to import). The app's own context is used only once the logger
        levels pane opens, and importing rclpy costs 0.1-0.2 s of CPU, which would come before
        the app's first frame."""
        check_domain_id(os.environ)
        # Before the first participant of the process: Fast DDS reads its profiles once. (And
        # before the intake process is started: it inherits them.)
        os.environ.update(reader_profile_environment(os.environ))
        self._args, self._domain_id = args, domain_id
        self._context: Any = None
        self._nodes: list[Any] = []
        self._lock = threading.Lock()
        self._closed = False
        if deferred:
            require_rclpy()
        else:
            self._start()

    def _start(self) -> Any:
        """The context, made now if it was not yet (``RosUnavailable`` when rclpy cannot be imported)."""
        with self._lock:
            if self._context is None:
                if self._closed:
                    raise RuntimeError("ROS 2 was shut down")
                rclpy = load_rclpy()
                from rclpy.context import Context
                from rclpy.signals import SignalHandlerOptions

                context = Context()
                rclpy.init(
                    args=self._args,
                    context=context,
                    domain_id=self._domain_id,
                    signal_handler_options=SignalHandlerOptions.NO,
                )
                self._context = context
            return self._context

    @property
    def context(self) -> Any:
        return self._start()

    def create_node(self, role: str, *, name: str | None = None, enable_rosout: bool = False, **options: Any) -> Any:
        """A hidden node (its name starts with ``_``) unique to this process, or, given
        ``name``, a node of that name (``console-tui rosout`` is a node people see)."""
        context = self.context
        from rclpy.node import Node

        node_name = name or f"_console_tui_{role}_{os.getpid()}"
        node = Node(node_name, context=context, enable_rosout=enable_rosout, **options)
        with self._lock:
            self._nodes.append(node)
        return node

    @property
    def ok(self) -> bool:
        return not self._closed and (self._context is None or self._context.ok())

    def shutdown(self) -> None:
        with self._lock:
            if self._closed:
                return
            self._closed = True
            nodes, self._nodes = self._nodes, []
            context = self._context
        for node in nodes:
            try:
                node.destroy_node()
            except Exception:
                pass
        if context is not None:
            try:
                context.try_shutdown()
            except Exception:
                pass


def start_ros2(domain_id: int | None = None, *, deferred: bool = False) -> RosRuntime:
    """An rclpy context of our own (``RosRuntime``), on ``domain_id`` (default ``ROS_DOMAIN_ID``'s);
    ``RosUnavailable`` with advice if ROS 2 cannot start. ``deferred``: rclpy is imported at the
    context's first use (see ``RosRuntime``)."""
    try:
        return RosRuntime(domain_id=domain_id, deferred=deferred)
    except RosUnavailable:
        raise
    except Exception as error:  # rclpy present but broken (wrong RMW, bad environment)
        raise RosUnavailable(f"ROS 2 could not start: {type(error).__name__}: {error}") from None
