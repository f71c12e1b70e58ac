"""The take loop in C (``take_loop.c``), compiled on this machine the first time it is needed.

Taking a serialized message through rclpy costs a pybind11 call, a message-info dict and a
Python sequence-number check: about 3-5 µs a message on the 2-core test machine, against
1.0-1.7 µs for the same takes in C (``benchmarks/take_loop.py``). At a publisher's
maximum rate that difference decides whether the console keeps up.

``load()`` builds the loop against the headers of the rcl that rclpy has loaded (found
next to its ``librcl.so``: ``<prefix>/lib`` and ``<prefix>/include``, as both ROS installs
and the PyPI wheels lay them out), with the C compiler Python was built with, into
``$XDG_CACHE_HOME/console-tui`` (else ``~/.cache/console-tui``), named by a hash of
everything it was built from; later starts load it from there. Without a compiler,
Python's headers or rcl's (or with ``CONSOLE_TUI_COMPILED_TAKE=0``) the intake takes
through rclpy, as before: ``load()`` returns ``None`` and says why.
"""

from __future__ import annotations

import hashlib
import importlib.machinery
import importlib.util
import os
import shutil
import subprocess
import sys
import sysconfig
import tempfile
from collections.abc import Callable
from pathlib import Path

SOURCE = Path(__file__).with_name("take_loop.c")
MODULE = "console_tui_take_loop"
#: ``0`` keeps rclpy's take (to compare the two, or if the compiled one misbehaves).
SWITCH = "CONSOLE_TUI_COMPILED_TAKE"
BUILD_TIMEOUT_S = 60.0
_LIBRARIES = ("rcl", "rmw", "rcutils")

#: ``take(pointer, limit, last_seen[, infos]) -> (messages, lost)``; see take_loop.c.
TakeFunction = Callable[..., tuple[list[bytes], int]]

_loaded: tuple[TakeFunction | None, str] | None = None


def load() -> tuple[TakeFunction | None, str]:
    """The compiled take function and ``""``, or ``None`` and why not (built once, then cached)."""
    global _loaded
    if _loaded is None:
        try:
            _loaded = _load()
        except Exception as error:  # never worth stopping the intake for
            _loaded = (None, f"{type(error).__name__}: {error}")
    return _loaded


def _load() -> tuple[TakeFunction | None, str]:
    if os.environ.get(SWITCH, "1") == "0":
        return None, f"{SWITCH}=0"
    library = loaded_rcl()
    if library is None:
        return None, "rclpy's librcl.so is not among this process's libraries"
    built = cache_dir() / f"take_loop_{build_key(library)}{_suffix()}"
    if not built.exists():
        problem = build(library, built)
        if problem:
            return None, problem
    loader = importlib.machinery.ExtensionFileLoader(MODULE, str(built))
    spec = importlib.util.spec_from_file_location(MODULE, built, loader=loader)
    assert spec is not None
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    take: TakeFunction = module.take
    return take, ""


def loaded_rcl() -> Path | None:
    """The ``librcl.so`` this process has loaded (importing rclpy loads it), on Linux."""
    import rclpy.impl.implementation_singleton  # noqa: F401  (loads librcl)

    try:
        maps = Path("/proc/self/maps").read_text()
    except OSError:
        return None
    for line in maps.splitlines():
        path = line.rpartition(" ")[2]
        if path.endswith("/librcl.so"):
            return Path(path)
    return None


def cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "console-tui"


def _suffix() -> str:
    return str(sysconfig.get_config_var("EXT_SUFFIX") or ".so")


def build_key(library: Path) -> str:
    """What the built file depends on: the C source, this Python, and the rcl it links to."""
    facts = os.stat(library)
    digest = hashlib.sha256(SOURCE.read_bytes())
    digest.update(f"{sys.version}|{_suffix()}|{library.resolve()}|{facts.st_size}|{facts.st_mtime_ns}".encode())
    return digest.hexdigest()[:16]


def _compiler() -> str | None:
    words = (os.environ.get("CC") or str(sysconfig.get_config_var("CC") or "cc")).split()
    return shutil.which(words[0]) if words else None


def build(library: Path, target: Path) -> str:
    """Compile ``take_loop.c`` into ``target``; ``""``, or what went wrong."""
    compiler = _compiler()
    if compiler is None:
        return "no C compiler (cc)"
    python_include = Path(sysconfig.get_paths()["include"])
    if not (python_include / "Python.h").exists():
        return f"no Python.h in {python_include} (python3-dev)"
    lib_dir = library.parent
    include = lib_dir.parent / "include"
    if not (include / "rcl" / "rcl" / "subscription.h").exists() and not (include / "rcl" / "subscription.h").exists():
        return f"no rcl headers in {include}"
    includes = [f"-I{path}" for path in sorted(include.iterdir()) if path.is_dir()] + [f"-I{include}"]
    target.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
    with tempfile.TemporaryDirectory(dir=target.parent) as work:
        partial = Path(work) / target.name
        command = [
            compiler,
            "-O2",
            "-shared",
            "-fPIC",
            "-o",
            str(partial),
            str(SOURCE),
            f"-I{python_include}",
            *includes,
            f"-L{lib_dir}",
            *(f"-l{name}" for name in _LIBRARIES),
            f"-Wl,-rpath,{lib_dir}",
        ]
        try:
            done = subprocess.run(command, capture_output=True, text=True, timeout=BUILD_TIMEOUT_S, check=False)
        except (OSError, subprocess.TimeoutExpired) as error:
            return f"compiling take_loop.c: {error}"
        if done.returncode != 0:
            lines = [line for line in done.stderr.splitlines() if line.strip()]
            return f"compiling take_loop.c failed: {lines[-1] if lines else done.returncode}"
        os.replace(partial, target)  # whole or not at all, when two processes build at once
    return ""
