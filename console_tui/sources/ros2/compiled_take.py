"""The take loop in C (``take_loop.c``), compiled on this machine the first time it is needed.

Taking a serialized message through rclpy costs a pybind11 call, a message-info dict and a
Python sequence-number check: about three times what the same takes cost in C
(``benchmarks/take_loop.py``; docs/architecture.md, "The take loop in C"). At a publisher's
maximum rate that difference decides whether the console keeps up.

``load()`` builds the loop against the headers of the rcl that rclpy has loaded (found
next to its ``librcl.so``: ``<prefix>/lib`` and ``<prefix>/include``, as both ROS installs
and the PyPI wheels lay them out), with the C compiler Python was built with, into
``$XDG_CACHE_HOME/console-tui`` (else ``~/.cache/console-tui``), named by a hash of
everything it was built from; later starts load it from there. Without a compiler,
Python's headers or rcl's (or with ``CONSOLE_TUI_COMPILED_TAKE=0``) the intake takes
through rclpy: ``load()`` returns ``None`` and says why.

What the cache trusts: a built file is loaded only from a cache directory that is a real
directory (not a link) owned by the user and writable by nobody else, and only if the file
itself is a regular file owned by the user and writable by nobody else. Otherwise the loop
is built into a fresh private directory, loaded from there, and ``load()`` says why. Files
of the loop's shape that no start has used for ``PRUNE_AFTER_S`` (other venvs, other rcl
versions) are removed from the cache.

The build is bounded (``BUILD_TIMEOUT_S``, the compiler's whole process group killed at
the end of it) and runs beside the intake: ``start_loading()`` starts it, ``loaded_now()``
says whether it is done, and meanwhile the intake takes through rclpy.
"""

from __future__ import annotations

import hashlib
import importlib.machinery
import importlib.util
import os
import re
import shutil
import signal
import stat
import subprocess
import sys
import sysconfig
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path

SOURCE = Path(__file__).with_name("take_loop.c")
MODULE = "console_tui_take_loop"
#: ``0`` keeps rclpy's take (to compare the two, or if the compiled one misbehaves).
SWITCH = "CONSOLE_TUI_COMPILED_TAKE"
BUILD_TIMEOUT_S = 60.0
#: A built loop no start has used for this long is removed from the cache.
PRUNE_AFTER_S = 30 * 86400.0
_BUILT = re.compile(r"take_loop_[0-9a-f]{16}\..*so\Z")
_LIBRARIES = ("rcl", "rmw", "rcutils")

#: ``take(pointer, limit, last_seen[, infos]) -> (messages, lost)``; see take_loop.c.
TakeFunction = Callable[..., tuple[list[bytes], int]]

_loaded: tuple[TakeFunction | None, str] | None = None
_build_lock = threading.Lock()
_state_lock = threading.Lock()
_loading: threading.Thread | None = None
#: The compiler's process while a build runs (``stop_building`` ends it).
_compiling: subprocess.Popen | None = None


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
    name = f"take_loop_{build_key(library)}{_suffix()}"
    cache = cache_dir()
    distrust = untrusted(cache, directory=True) if os.path.lexists(cache) else ""
    if distrust:
        if not may_build:
            return None
        with tempfile.TemporaryDirectory(prefix="console-tui-take-") as private:  # mode 0700
            built = Path(private) / name
            problem = build(library, built)
            if problem:
                return None, f"{distrust}; building elsewhere: {problem}"
            return _import(built), f"built into a private directory, as {distrust}"
    built = cache / name
    if built.exists() or built.is_symlink():
        distrust = untrusted(built, directory=False)
        if distrust:
            built.unlink()  # ours to remove: the directory is ours and no one else's
    if not built.exists():
        if not may_build:
            return None
        problem = build(library, built)
        if problem:
            return None, problem
    os.utime(built)  # used now: not pruned
    prune(cache, keep=built)
    return _import(built), ""


def untrusted(path: Path, *, directory: bool) -> str:
    """Why ``path`` must not be trusted to load code from, or "": it must be ours (this
    user's), writable by no one else, and a real directory or regular file (not a link)."""
    try:
        info = os.lstat(path)
    except OSError as error:
        return f"{path}: {error.strerror or error}"
    kind_ok = stat.S_ISDIR(info.st_mode) if directory else stat.S_ISREG(info.st_mode)
    if not kind_ok:
        return f"{path} is not a {'directory' if directory else 'regular file'}"
    if info.st_uid != os.geteuid():
        return f"{path} belongs to another user (uid {info.st_uid})"
    if info.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        return f"{path} is writable by others"
    return ""


def prune(cache: Path, *, keep: Path, now: float | None = None) -> None:
    """Remove built loops of ours that no start has used for ``PRUNE_AFTER_S``."""
    limit = (time.time() if now is None else now) - PRUNE_AFTER_S
    try:
        entries = list(os.scandir(cache))
    except OSError:
        return
    for entry in entries:
        if entry.name == keep.name or not _BUILT.match(entry.name):
            continue
        try:
            info = entry.stat(follow_symlinks=False)
            if stat.S_ISREG(info.st_mode) and info.st_uid == os.geteuid() and info.st_mtime < limit:
                os.unlink(entry.path)
        except OSError:
            pass


def _import(built: Path) -> TakeFunction:
    loader = importlib.machinery.ExtensionFileLoader(MODULE, str(built))
    spec = importlib.util.spec_from_file_location(MODULE, built, loader=loader)
    assert spec is not None
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    take: TakeFunction = module.take
    return take


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
        returncode, stderr = _run_bounded(command)
        if returncode is None:
            return f"compiling take_loop.c took longer than {BUILD_TIMEOUT_S:g} s: stopped"
        if returncode != 0:
            lines = [line for line in stderr.splitlines() if line.strip()]
            return f"compiling take_loop.c failed: {lines[-1] if lines else returncode}"
        os.replace(partial, target)  # whole or not at all, when two processes build at once
    return ""


def _run_bounded(command: list[str]) -> tuple[int | None, str]:
    """Run the compiler in a process group of its own; its status and stderr, or ``None``
    when it took longer than ``BUILD_TIMEOUT_S`` (the whole group is killed then)."""
    try:
        process = subprocess.Popen(
            command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True
        )
    except OSError as error:
        return 1, f"compiling take_loop.c: {error.strerror or error}"
    global _compiling
    _compiling = process
    try:
        _out, stderr = process.communicate(timeout=BUILD_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        _kill_group(process)
        process.communicate()
        return None, ""
    finally:
        _compiling = None
    return process.returncode, stderr


def stop_building() -> None:
    """End a build under way (the compiler's whole process group): the intake is stopping,
    and the compiler runs in a session of its own, so it would outlive it."""
    process = _compiling
    if process is not None and process.poll() is None:
        _kill_group(process)


def _kill_group(process: subprocess.Popen) -> None:
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
