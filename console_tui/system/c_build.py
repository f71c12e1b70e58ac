"""The intake's loops in C, compiled on this machine the first time they are needed, cached.

Two live sources have a loop in C for the path every message takes: ROS 2's take loop
(``ros2/compiled_take.py``) and ROS 1's frame loop (``ros1/compiled_frames.py``). Each is one
C file built with the C compiler Python was built with into ``$XDG_CACHE_HOME/console-tui``
(else ``~/.cache/console-tui``), named by a hash of everything it was built from; later
starts load it from there. This module is what they share: where the cache is, whether it
may be trusted, building with a bound on time, loading, and pruning old builds.

What the cache trusts: a built file is loaded only from a cache directory that is a real
directory (not a link) owned by the user and writable by nobody else, and only if the file
itself is a regular file owned by the user and writable by nobody else. Otherwise the loop
is built into a fresh private directory and loaded from there, and ``load_or_build`` says
why. Files of a loop's shape that no start has used for ``PRUNE_AFTER_S`` (other venvs,
other versions) are removed from the cache.

The compiler runs in a process group of its own, killed whole at its time limit;
``stop_building`` ends a build under way (the intake is stopping: it would outlive it).
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import re
import shutil
import signal
import stat
import subprocess
import sysconfig
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from types import ModuleType

#: A built loop no start has used for this long is removed from the cache.
PRUNE_AFTER_S = 30 * 86400.0

#: The compilers' processes while builds run (``stop_building`` ends them).
_compiling: set[subprocess.Popen] = set()


def cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "console-tui"


def suffix() -> str:
    """The file name ending of an extension module for this Python."""
    return str(sysconfig.get_config_var("EXT_SUFFIX") or ".so")


def built_pattern(stem: str) -> re.Pattern[str]:
    """The names of built files of the loop ``stem`` (``<stem>_<16 hex digits>.<suffix>``)."""
    return re.compile(rf"{re.escape(stem)}_[0-9a-f]{{16}}\..*so\Z")


def compiler() -> str | None:
    words = (os.environ.get("CC") or str(sysconfig.get_config_var("CC") or "cc")).split()
    return shutil.which(words[0]) if words else None


def python_include() -> Path | None:
    """Python's headers, or ``None`` when ``Python.h`` is not there (python3-dev)."""
    include = Path(sysconfig.get_paths()["include"])
    return include if (include / "Python.h").exists() else None


def load_or_build(name: str, stem: str, module: str, build: Callable[[Path], str]) -> tuple[ModuleType | None, str]:
    """The module ``module`` from the cached file ``name``, built first by ``build(target)``
    (which returns ``""`` or what went wrong) when it is not there: the module and ``""``
    (or a note on where it was built), or ``None`` and why not."""
    loaded = load_cached(name, stem, module)
    if loaded is not None:
        return loaded
    cache = cache_dir()
    distrust = untrusted(cache, directory=True) if os.path.lexists(cache) else ""
    if distrust:
        with tempfile.TemporaryDirectory(prefix="console-tui-build-") as private:  # mode 0700
            built = Path(private) / name
            problem = build(built)
            if problem:
                return None, f"{distrust}; building elsewhere: {problem}"
            return import_built(module, built), f"built into a private directory, as {distrust}"
    built = cache / name
    problem = build(built)
    if problem:
        return None, problem
    return _used(built, stem, module), ""


def load_cached(name: str, stem: str, module: str) -> tuple[ModuleType, str] | None:
    """The module from the cached file ``name`` if the cache and the file may be trusted
    (a file that may not is removed: the directory is ours and no one else's), else ``None``."""
    cache = cache_dir()
    if os.path.lexists(cache) and untrusted(cache, directory=True):
        return None
    built = cache / name
    if (built.exists() or built.is_symlink()) and untrusted(built, directory=False):
        built.unlink()
    if not built.exists():
        return None
    return _used(built, stem, module), ""


def _used(built: Path, stem: str, module: str) -> ModuleType:
    os.utime(built)  # used now: not pruned
    prune(built.parent, keep=built, pattern=built_pattern(stem))
    return import_built(module, built)


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


def prune(cache: Path, *, keep: Path, pattern: re.Pattern[str], now: float | None = None) -> None:
    """Remove built files of ours named like ``pattern`` that no start has used for ``PRUNE_AFTER_S``."""
    limit = (time.time() if now is None else now) - PRUNE_AFTER_S
    try:
        entries = list(os.scandir(cache))
    except OSError:
        return
    for entry in entries:
        if entry.name == keep.name or not pattern.match(entry.name):
            continue
        try:
            info = entry.stat(follow_symlinks=False)
            if stat.S_ISREG(info.st_mode) and info.st_uid == os.geteuid() and info.st_mtime < limit:
                os.unlink(entry.path)
        except OSError:
            pass


def import_built(module: str, built: Path) -> ModuleType:
    loader = importlib.machinery.ExtensionFileLoader(module, str(built))
    spec = importlib.util.spec_from_file_location(module, built, loader=loader)
    assert spec is not None
    loaded = importlib.util.module_from_spec(spec)
    loader.exec_module(loaded)
    return loaded


def compile_module(source: Path, target: Path, timeout: float, flags: Sequence[str] = ()) -> str:
    """Compile the C file ``source`` into the extension module ``target`` (Python's headers,
    then ``flags``), within ``timeout`` seconds; ``""``, or what went wrong."""
    cc = compiler()
    if cc is None:
        return "no C compiler (cc)"
    include = python_include()
    if include is None:
        return "no Python.h (python3-dev)"
    target.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
    with tempfile.TemporaryDirectory(dir=target.parent) as work:
        partial = Path(work) / target.name
        command = [cc, "-O2", "-shared", "-fPIC", "-o", str(partial), str(source), f"-I{include}", *flags]
        returncode, stderr = run_bounded(command, timeout, source.name)
        if returncode is None:
            return f"compiling {source.name} took longer than {timeout:g} s: stopped"
        if returncode != 0:
            lines = [line for line in stderr.splitlines() if line.strip()]
            return f"compiling {source.name} failed: {lines[-1] if lines else returncode}"
        os.replace(partial, target)  # whole or not at all, when two processes build at once
    return ""


def run_bounded(command: list[str], timeout: float, what: str) -> tuple[int | None, str]:
    """Run the compiler in a process group of its own; its status and stderr, or ``None``
    when it took longer than ``timeout`` (the whole group is killed then)."""
    try:
        process = subprocess.Popen(
            command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True
        )
    except OSError as error:
        return 1, f"compiling {what}: {error.strerror or error}"
    _compiling.add(process)
    try:
        _out, stderr = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        _kill_group(process)
        process.communicate()
        return None, ""
    finally:
        _compiling.discard(process)
    return process.returncode, stderr


def stop_building() -> None:
    """End the builds under way (each compiler's whole process group): the intake is
    stopping, and a compiler runs in a session of its own, so it would outlive it."""
    for process in list(_compiling):
        if process.poll() is None:
            _kill_group(process)


def _kill_group(process: subprocess.Popen) -> None:
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
