"""What the tests of the intake's loops in C (``compiled_take``, ``compiled_frames``) check
alike: built once into the cache and loaded from it after, and never loaded from a cache
others can write."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest


def built_once_then_cached(module: Any, root: Path, monkeypatch: pytest.MonkeyPatch, stem: str) -> None:
    """``module.load()`` builds one file named ``<stem>_…`` into the cache under ``root``;
    loaded again without a compiler, it comes from there and nothing is built."""
    function, note = module.load()
    assert function is not None and note == ""
    built = list((root / "console-tui").iterdir())
    assert len(built) == 1 and built[0].name.startswith(f"{stem}_")
    monkeypatch.setattr(module, "_loaded", None)
    monkeypatch.setenv("CC", "/nonexistent/cc")  # no compiler now: only the cache can serve
    function, note = module.load()
    assert function is not None and note == ""
    assert list((root / "console-tui").iterdir()) == built


def not_loaded_from_a_shared_cache(module: Any, root: Path, name: str) -> None:
    """A file planted as ``name`` in a cache another user can write is never loaded: the loop
    is built into a private directory, ``load()`` says why, and the planted file is left alone."""
    cache = root / "console-tui"
    cache.mkdir()
    planted = cache / name
    planted.write_bytes(b"not an ELF file: loading it fails loudly")
    cache.chmod(0o777)
    function, note = module.load()
    assert function is not None, note
    assert "private directory" in note and "writable by others" in note
    assert planted.read_bytes().startswith(b"not an ELF")  # not ours to touch
    assert [p.name for p in cache.iterdir()] == [planted.name]


def as_in_a_new_process(module: Any, monkeypatch: pytest.MonkeyPatch, root: Path) -> Path:
    """``module`` as a new process has it (nothing loaded or loading, not switched off), with
    an empty cache under ``root``."""
    monkeypatch.setattr(module, "_loaded", None)
    monkeypatch.setattr(module, "_loading", None)
    monkeypatch.setenv("XDG_CACHE_HOME", str(root))
    monkeypatch.delenv(module.SWITCH, raising=False)
    return root
