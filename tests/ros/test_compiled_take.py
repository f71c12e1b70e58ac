"""Building the take loop in C (``compiled_take``): built once into the cache, reused, and
skipped with a reason where it cannot be built. Taking through it: test_ros2_live_source.py."""

from __future__ import annotations

import os
import time

import pytest

from console_tui.sources.ros2 import compiled_take

from support.compiled import as_in_a_new_process, built_once_then_cached, not_loaded_from_a_shared_cache

pytestmark = pytest.mark.ros2


@pytest.fixture
def fresh(monkeypatch, tmp_path):
    """``compiled_take`` as in a new process, with an empty cache in ``tmp_path``."""
    return as_in_a_new_process(compiled_take, monkeypatch, tmp_path)


def test_it_is_built_once_and_then_loaded_from_the_cache(fresh, monkeypatch):
    built_once_then_cached(compiled_take, fresh, monkeypatch, "take_loop")


def test_without_a_compiler_it_says_why_and_the_intake_takes_through_rclpy(fresh, monkeypatch):
    monkeypatch.setenv("CC", "/nonexistent/cc")
    assert compiled_take.load() == (None, "no C compiler (cc)")
    assert not (fresh / "console-tui").exists()


def test_a_compiler_that_fails_leaves_nothing_half_built(fresh, monkeypatch):
    script = fresh / "broken-cc"
    script.write_text("#!/bin/sh\necho 'take_loop.c:1: error: no' >&2\nexit 1\n")
    script.chmod(0o755)
    monkeypatch.setenv("CC", str(script))
    assert compiled_take.load() == (None, "compiling take_loop.c failed: take_loop.c:1: error: no")
    assert list((fresh / "console-tui").iterdir()) == []


def test_it_can_be_switched_off(fresh, monkeypatch):
    monkeypatch.setenv(compiled_take.SWITCH, "0")
    assert compiled_take.load() == (None, "CONSOLE_TUI_COMPILED_TAKE=0")


def test_a_cache_writable_by_others_is_not_loaded_from(fresh):
    library = compiled_take.loaded_rcl()
    assert library is not None
    name = f"take_loop_{compiled_take.build_key(library)}{compiled_take._suffix()}"
    not_loaded_from_a_shared_cache(compiled_take, fresh, name)


@pytest.mark.parametrize("how", ["group-writable", "another user's"])
def test_a_cached_file_not_ours_alone_is_built_again(fresh, how):
    cache = fresh / "console-tui"
    cache.mkdir(mode=0o700)
    library = compiled_take.loaded_rcl()
    assert library is not None
    planted = cache / f"take_loop_{compiled_take.build_key(library)}{compiled_take._suffix()}"
    planted.write_bytes(b"not an ELF file: loading it fails loudly")
    if how == "group-writable":
        planted.chmod(0o664)
    else:
        if os.geteuid() != 0:
            pytest.skip("needs root to give a file to another user")
        os.chown(planted, 65534, 65534)
    function, note = compiled_take.load()
    assert function is not None and note == ""
    assert not planted.read_bytes().startswith(b"not an ELF")


def test_old_builds_are_pruned_the_one_in_use_and_others_kept(fresh):
    function, _ = compiled_take.load()
    assert function is not None
    cache = fresh / "console-tui"
    (current,) = cache.iterdir()
    old = cache / "take_loop_0123456789abcdef.cpython-312-x86_64-linux-gnu.so"
    recent = cache / "take_loop_fedcba9876543210.cpython-312-x86_64-linux-gnu.so"
    other = cache / "notes.txt"
    for path in (old, recent, other):
        path.write_bytes(b"x")
    long_ago = time.time() - compiled_take.PRUNE_AFTER_S - 86400
    for path in (old, other):
        os.utime(path, (long_ago, long_ago))
    compiled_take.prune(cache, keep=current)
    assert sorted(p.name for p in cache.iterdir()) == sorted([current.name, recent.name, other.name])


def test_a_hanging_compiler_does_not_hold_the_intake(fresh, monkeypatch):
    """The build runs beside the intake: ``start_loading`` returns at once, and a compiler
    that hangs is stopped at the build's time limit (with its whole process group)."""
    script = fresh / "hanging-cc"
    script.write_text("#!/bin/sh\nsleep 100 &\nwait\n")
    script.chmod(0o755)
    monkeypatch.setenv("CC", str(script))
    monkeypatch.setattr(compiled_take, "BUILD_TIMEOUT_S", 1.0)
    compiled_take.start_loading()
    assert compiled_take._loading is not None
    deadline = time.monotonic() + 60
    while compiled_take.loaded_now() is None:
        assert time.monotonic() < deadline, "the build was never stopped"
        time.sleep(0.05)
    assert compiled_take.loaded_now() == (None, "compiling take_loop.c took longer than 1 s: stopped")
