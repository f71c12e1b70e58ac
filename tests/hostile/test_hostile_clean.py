"""``console-tui clean`` against mis-set paths and hostile names (issue 33, items 5 and 6; issue
29's wording): it refuses /, the home directory and directories holding anything but ROS logs,
names the resolved path, removes only ROS logs by their shape, and never prints a name raw."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

from console_tui.cli import main

RUN = "0b8c1f2e-1111-2222-3333-444455556666"
DAY = 86400.0


def make_run(log: Path, name: str = RUN, size: int = 4600, age_days: float = 3) -> Path:
    run = log / name
    run.mkdir(parents=True)
    (run / "rosout.log").write_bytes(b"x" * size)
    moment = time.time() - age_days * DAY
    for path in (run / "rosout.log", run):
        os.utime(path, (moment, moment))
    return run


def clean(*args: str, home: Path, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    environ = {"PATH": "/usr/bin:/bin", "HOME": str(home), **(env or {})}
    return subprocess.run(
        [sys.executable, "-m", "console_tui", "clean", *args],
        capture_output=True,
        text=True,
        timeout=120,
        env=environ,
        stdin=subprocess.DEVNULL,
    )


def test_root_and_home_are_never_log_directories(tmp_path):
    home = tmp_path / "home"
    (home / ".ssh").mkdir(parents=True)
    (home / ".ssh" / "id_ed25519").write_text("key")
    make_run(home / ".ros" / "log")
    for env, said in (({"ROS_LOG_DIR": "/"}, "root directory"), ({"ROS_LOG_DIR": str(home)}, "home directory")):
        for args in (["check"], ["purge"]):
            result = clean(*args, home=home, env=env)
            assert result.returncode == 1, (env, args, result.stdout, result.stderr)
            assert said in result.stderr and "nothing done" in result.stderr
    result = clean("purge", "--yes", "--force", home=home, env={"ROS_LOG_DIR": str(home)})
    assert result.returncode == 1
    assert (home / ".ssh" / "id_ed25519").exists() and (home / ".ros" / "log" / RUN).exists()


def test_a_linked_log_directory_is_named_resolved_and_its_other_files_are_kept(tmp_path):
    home = tmp_path / "home"
    target = tmp_path / "elsewhere"
    make_run(target)
    (target / "notes.txt").write_text("mine")
    (home / ".ros").mkdir(parents=True)
    (home / ".ros" / "log").symlink_to(target)
    result = clean("purge", "--yes", home=home)
    assert result.returncode == 1 and "notes.txt" in result.stderr and "not a log directory" in result.stderr
    assert f"-> {target}" in result.stderr
    assert (target / RUN).exists()
    result = clean("purge", "--yes", "--force", home=home)
    assert result.returncode == 0, result.stderr
    assert f"-> {target}" in result.stdout
    assert sorted(p.name for p in target.iterdir()) == ["notes.txt"]


def test_names_are_shown_inert(tmp_path):
    log = tmp_path / "log"
    hostile_run = "2026-11-10-10-00-00-123456-\x1b]0;pwned\x07-42"  # launch-shaped: a ROS log
    make_run(log, hostile_run)
    (log / "\x1b]52;c;QUFB\x07\nforged 1.0K line").mkdir()  # not a ROS log
    result = clean("check", "--dir", str(log), home=tmp_path)
    assert result.returncode == 0, result.stderr
    for stream in (result.stdout, result.stderr):
        assert "\x1b" not in stream and "\x07" not in stream
    assert len(result.stdout.splitlines()) == 4  # total, the other entry, heading, the run: nothing forged
    result = clean("purge", "--dir", str(log), "--force", "--yes", home=tmp_path)
    assert result.returncode == 0
    assert "\x1b" not in result.stdout + result.stderr and "\x07" not in result.stdout + result.stderr
    assert [p.name for p in log.iterdir()] == ["\x1b]52;c;QUFB\x07\nforged 1.0K line"]


def test_purge_words_one_run_and_success(tmp_path, capsys, monkeypatch):
    log = tmp_path / "log"
    make_run(log)
    (log / "latest").symlink_to(log / RUN)
    monkeypatch.setattr("sys.stdin", open(os.devnull))
    assert main(["clean", "purge", "--dir", str(log)]) == 3
    assert "Remove this run and 1 link (4.5K) from" in capsys.readouterr().err
    assert main(["clean", "check", "--dir", str(log)]) == 0
    assert capsys.readouterr().out.splitlines()[0] == f"{log}: 4.5K in 1 run"
    assert main(["clean", "purge", "--dir", str(log), "--older-than", "1d", "--yes"]) == 0
    out = capsys.readouterr().out
    assert f"Removed 1 run (4.5K) from {log}." in out and "failure" not in out
    assert not log.exists() or list(log.iterdir()) == []


def test_keep_size_keeps_a_run_still_being_written(tmp_path, capsys):
    log = tmp_path / "log"
    make_run(log, RUN, size=5000, age_days=10)
    fresh = "9f9e8d7c-1111-2222-3333-444455556666"
    make_run(log, fresh, size=5000, age_days=0)
    assert main(["clean", "purge", "--dir", str(log), "--keep-size", "0", "--yes"]) == 0
    assert [p.name for p in log.iterdir()] == [fresh]


def test_check_help_and_bad_age_belong_to_their_subcommand(tmp_path):
    help_text = clean("check", "--help", home=tmp_path).stdout
    assert "exit status:" in help_text and "not confirmed" not in help_text and "removed" not in help_text
    result = clean("purge", "--older-than", "soon", "--dir", str(tmp_path), home=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("usage: console-tui clean purge") and "--older-than" in result.stderr
