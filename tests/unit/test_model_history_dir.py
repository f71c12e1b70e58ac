"""The history's directories: private (0700, files 0600), refused when another user could
write them, and those of sessions that were killed removed by the next start."""

from __future__ import annotations

import os
import stat
import subprocess
import sys

import pytest

from console_tui.model.store.history_dir import (
    UnsafeDirectory,
    close_spill,
    open_session_spill,
    private_directory,
    session_directory,
)
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord


def test_a_session_gets_a_private_directory_removed_at_the_end(tmp_path):
    spill, directory, why = open_session_spill(tmp_path / "history")
    assert spill is not None and directory is not None and why == ""
    assert stat.S_IMODE(os.stat(directory).st_mode) == 0o700
    store = LogStore(spill=spill)
    store.extend_records(LogRecord(i, 20, "n", f"m{i}") for i in range(CHUNK_SIZE + 1))
    segments = list(directory.iterdir())
    assert segments and all(stat.S_IMODE(os.stat(path).st_mode) == 0o600 for path in segments)
    close_spill(spill, directory)
    assert not directory.exists()


def test_a_directory_others_can_write_is_refused_with_why(tmp_path):
    base = tmp_path / "history"
    base.mkdir(mode=0o700)
    os.chmod(base, 0o777)
    spill, directory, why = open_session_spill(base)
    assert spill is None and directory is None
    assert why == f"{base} can be written by other users (mode 777)"
    os.chmod(base, 0o700)
    os.chmod(tmp_path, 0o775)  # the directory above it counts too
    with pytest.raises(UnsafeDirectory, match="can be written by other users"):
        private_directory(base)
    os.chmod(tmp_path, 0o700)


def test_a_link_is_refused(tmp_path):
    real = tmp_path / "real"
    real.mkdir(mode=0o700)
    (tmp_path / "history").symlink_to(real)
    with pytest.raises(UnsafeDirectory, match="symbolic link"):
        private_directory(tmp_path / "history")


@pytest.mark.skipif(os.geteuid() != 0, reason="only root can give a directory to another user")
def test_another_users_directory_is_refused(tmp_path):
    base = tmp_path / "history"
    base.mkdir(mode=0o700)
    os.chown(base, 65534, 65534)
    with pytest.raises(UnsafeDirectory, match="belongs to another user"):
        private_directory(base)


def test_the_directories_of_sessions_that_were_killed_go(tmp_path):
    base = tmp_path / "history"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    stale = base / f"session-{int(dead.stdout)}-abc"
    stale.mkdir(parents=True, mode=0o700)
    (stale / "segment-000000.ctc").write_bytes(b"x")
    os.chmod(base, 0o700)
    mine = session_directory(base)
    assert not stale.exists() and mine.exists()


def test_a_shared_directory_with_the_sticky_bit_may_hold_ours(tmp_path):
    shared = tmp_path / "shared"
    shared.mkdir()
    os.chmod(shared, 0o1777)  # as /tmp
    assert private_directory(shared / "history").is_dir()
    os.chmod(shared, 0o777)  # without the sticky bit: anyone could replace ours
    with pytest.raises(UnsafeDirectory, match="can be written by other users"):
        private_directory(shared / "history")
