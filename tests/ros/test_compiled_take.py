"""Building the take loop in C (``compiled_take``): built once into the cache, reused, and
skipped with a reason where it cannot be built. Taking through it: test_ros2_live_source.py."""

from __future__ import annotations

import pytest

from console_tui.sources.ros2 import compiled_take

pytestmark = pytest.mark.ros2


@pytest.fixture
def fresh(monkeypatch, tmp_path):
    """``compiled_take`` as in a new process, with an empty cache in ``tmp_path``."""
    monkeypatch.setattr(compiled_take, "_loaded", None)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.delenv(compiled_take.SWITCH, raising=False)
    return tmp_path


def test_it_is_built_once_and_then_loaded_from_the_cache(fresh, monkeypatch):
    function, problem = compiled_take.load()
    assert function is not None and problem == ""
    built = list((fresh / "console-tui").iterdir())
    assert len(built) == 1 and built[0].name.startswith("take_loop_")
    monkeypatch.setattr(compiled_take, "_loaded", None)
    monkeypatch.setenv("CC", "/nonexistent/cc")  # no compiler now: only the cache can serve
    function, problem = compiled_take.load()
    assert function is not None and problem == ""
    assert list((fresh / "console-tui").iterdir()) == built


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
