"""The take loop in C (``take_loop.c``), compiled on this machine the first time it is needed.

``load()`` builds the loop against the headers of the rcl that rclpy has loaded (found next to
its ``librcl.so``: ``<prefix>/lib`` and ``<prefix>/include``, as both ROS installs and the PyPI
wheels lay them out), as ``c_build`` builds and caches the intake's loops in C (named by a hash
of everything it was built from; a cache that may not be trusted is not loaded from); later
starts load it from there. Without a compiler, Python's headers or rcl's (or with
``CONSOLE_TUI_COMPILED_TAKE=0``) ``load()`` returns ``None`` and says why, and the intake takes
through rclpy. The build is bounded (``BUILD_TIMEOUT_S``, the compiler's whole process group
killed at the end of it) and runs beside the intake: ``start_loading()`` starts it,
``loaded_now()`` says whether it is done. Why in C: docs/decisions/0004-take-loop-in-c.md.
"""

from __future__ import annotations

import hashlib
import os
import sys
import threading
from collections.abc import Callable
from pathlib import Path

from ...system import c_build
from ...system.c_build import PRUNE_AFTER_S, stop_building

__all__ = ["PRUNE_AFTER_S", "load", "loaded_now", "prune", "start_loading", "stop_building"]

SOURCE = Path(__file__).with_name("take_loop.c")
MODULE = "console_tui_take_loop"
STEM = "take_loop"
#: ``0`` keeps rclpy's take (to compare the two, or if the compiled one misbehaves).
SWITCH = "CONSOLE_TUI_COMPILED_TAKE"
BUILD_TIMEOUT_S = 60.0
_LIBRARIES = ("rcl", "rmw", "rcutils")

#: ``take(pointer, limit, last_seen[, infos]) -> (messages, lost)``; see take_loop.c.
TakeFunction = Callable[..., tuple[list[bytes], int]]

_loaded: tuple[TakeFunction | None, str] | None = None
_build_lock = threading.Lock()
_state_lock = threading.Lock()
_loading: threading.Thread | None = None


def load() -> tuple[TakeFunction | None, str]:
    """The compiled take function and ``""`` (or a note on how it was built), or ``None``
    and why not (built once, then cached)."""
    global _loaded
    with _build_lock:
        if _loaded is None:
            _loaded = _guarded(_load) or (None, "not built")
        return _loaded


def start_loading() -> None:
    """What ``load()`` does, at once when nothing needs building, else on a thread of its
    own (once); ``loaded_now()`` says when it is done."""
    global _loading, _loaded
    with _state_lock:
        if _loaded is not None or _loading is not None:
            return
        _loading = threading.Thread(target=load, name="console-tui-take-loop-build", daemon=True)
    quick = _guarded(lambda: _load(may_build=False))
    if quick is not None:
        _loaded = quick
    else:
        _loading.start()


def _guarded(
    how: Callable[[], tuple[TakeFunction | None, str] | None],
) -> tuple[TakeFunction | None, str] | None:
    try:
        return how()
    except Exception as error:  # never worth stopping the intake for
        return None, f"{type(error).__name__}: {error}"


def loaded_now() -> tuple[TakeFunction | None, str] | None:
    """What ``load()`` gave, or ``None`` while it is still building."""
    return _loaded


def _load(*, may_build: bool = True) -> tuple[TakeFunction | None, str] | None:
    """What ``load()`` gives; ``None`` (only when not ``may_build``) when it must build."""
    if os.environ.get(SWITCH, "1") == "0":
        return None, f"{SWITCH}=0"
    library = loaded_rcl()
    if library is None:
        return None, "rclpy's librcl.so is not among this process's libraries"
    name = f"{STEM}_{build_key(library)}{_suffix()}"
    if not may_build:
        cached = c_build.load_cached(name, STEM, MODULE)
        return None if cached is None else (cached[0].take, cached[1])
    module, note = c_build.load_or_build(name, STEM, MODULE, lambda target: build(library, target))
    return (None if module is None else module.take), note


def prune(cache: Path, *, keep: Path, now: float | None = None) -> None:
    """Remove built take loops that no start has used for ``PRUNE_AFTER_S``."""
    c_build.prune(cache, keep=keep, pattern=c_build.built_pattern(STEM), now=now)


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


def _suffix() -> str:
    return c_build.suffix()


def build_key(library: Path) -> str:
    """What the built file depends on: the C source, this Python, and the rcl it links to."""
    facts = os.stat(library)
    digest = hashlib.sha256(SOURCE.read_bytes())
    digest.update(f"{sys.version}|{_suffix()}|{library.resolve()}|{facts.st_size}|{facts.st_mtime_ns}".encode())
    return digest.hexdigest()[:16]


def build(library: Path, target: Path) -> str:
    """Compile ``take_loop.c`` into ``target``; ``""``, or what went wrong."""
    flags = rcl_flags(library)
    if isinstance(flags, str):
        return flags
    return c_build.compile_module(SOURCE, target, BUILD_TIMEOUT_S, flags)


def rcl_flags(library: Path) -> list[str] | str:
    """The compiler's flags to build a module against the rcl at ``library`` (its headers
    and libraries), or why there are none."""
    lib_dir = library.parent
    include = lib_dir.parent / "include"
    if not (include / "rcl" / "rcl" / "subscription.h").exists() and not (include / "rcl" / "subscription.h").exists():
        return f"no rcl headers in {include}"
    includes = [f"-I{path}" for path in sorted(include.iterdir()) if path.is_dir()] + [f"-I{include}"]
    return [*includes, f"-L{lib_dir}", *(f"-l{name}" for name in _LIBRARIES), f"-Wl,-rpath,{lib_dir}"]
