"""Which arguments name the journal, what journalctl is asked, and its output read bounded
(a stand-in journalctl script on PATH: a real process printing what a damaged or hostile
journal could make it print)."""

from __future__ import annotations

import os
import stat
import time

import pytest

from console_tui.sources.journal import journalctl as journalctl_module
from console_tui.sources.journal.journal_location import (
    JOURNAL_MAGIC,
    JournalLocation,
    is_journal_file,
    is_journal_folder,
    journal_location,
    local_units,
)
from console_tui.sources.journal.journalctl import (
    DEFAULT_LINES,
    Journalctl,
    JournalQuery,
    JournalUnavailable,
    find_journalctl,
)
from console_tui.sources.locations import FILE, JOURNAL, split_locations


def test_journal_arguments_are_told_from_files(tmp_path):
    assert journal_location("journal:") == JournalLocation(live=True)
    assert journal_location("journal:nav.service,arm.service") == JournalLocation(
        live=True, units=("nav.service", "arm.service")
    )
    assert journal_location("journal:/var/log/journal/remote") == JournalLocation(
        live=True, path="/var/log/journal/remote"
    )
    assert journal_location(str(tmp_path)) is None
    assert journal_location("run.bag") is None
    kinds = split_locations(["a.log", "journal:nav", "b", "journal:"])
    assert kinds[FILE] == ["a.log", "b"] and kinds[JOURNAL] == ["journal:nav", "journal:"]
    assert [journal_location(text).units for text in kinds[JOURNAL]] == [("nav",), ()]


def test_journal_files_and_folders_by_name_magic_and_machine_folders(tmp_path):
    named = tmp_path / "system.journal"
    named.write_bytes(b"whatever")
    magic = tmp_path / "copy.bin"
    magic.write_bytes(JOURNAL_MAGIC + b"\0" * 8)
    other = tmp_path / "other.log"
    other.write_text("[INFO] [1.0] [x]: y\n")
    assert is_journal_file(named) and is_journal_file(magic) and not is_journal_file(other)
    assert journal_location(str(magic)) == JournalLocation(live=False, path=str(magic))
    remote = tmp_path / "remote"
    remote.mkdir()
    assert not is_journal_folder(remote)
    (remote / "remote-robot1.journal~").write_bytes(JOURNAL_MAGIC)
    assert is_journal_folder(remote)
    var_log_journal = tmp_path / "var"
    (var_log_journal / ("ab" * 16)).mkdir(parents=True)
    (var_log_journal / ("ab" * 16) / "system.journal").write_bytes(JOURNAL_MAGIC)
    assert is_journal_folder(var_log_journal) and not is_journal_folder(tmp_path / "missing")


def test_the_local_journal_is_one_source_whatever_its_units(tmp_path):
    nav, arm, everything = (JournalLocation(True, ("nav",)), JournalLocation(True, ("arm",)), JournalLocation(True))
    remote = JournalLocation(True, path=str(tmp_path))
    assert local_units([nav, arm, remote], ["cam", "nav"]) == [JournalLocation(True, ("nav", "arm", "cam")), remote]
    assert local_units([everything, nav], []) == [JournalLocation(True)]
    assert local_units([], ["cam"]) == [JournalLocation(True, ("cam",))]
    assert local_units([remote], []) == [remote]
    query = remote.query(since="-1h", follow=True)
    assert query.directory == str(tmp_path) and not query.files and not query.local


def test_what_journalctl_is_asked():
    follow = JournalQuery(units=("nav.service",), follow=True).arguments()
    assert follow[:3] == ["-o", "json", "--no-pager"] and "--follow" in follow
    assert "--unit=nav.service" in follow and f"--lines={DEFAULT_LINES}" in follow
    assert any(arg.startswith("--output-fields=MESSAGE,PRIORITY,") for arg in follow)
    since = JournalQuery(since="-1h", follow=True).arguments()
    assert "--since=-1h" in since and not any(arg.startswith("--lines") for arg in since)
    a_file = JournalQuery(files=("/x/a.journal",), follow=True).arguments()
    assert "--file=/x/a.journal" in a_file and "--no-tail" in a_file
    once = JournalQuery(directory="/x").arguments()
    assert "--directory=/x" in once and "--follow" not in once and "--no-tail" not in once
    assert JournalQuery(units=("a", "b"), since="today").describe() == "this machine's journal (a, b) since today"


def fake_journalctl(tmp_path, monkeypatch, body: str) -> None:
    """A ``journalctl`` on PATH that runs ``body`` (a Python program) whatever it is asked."""
    folder = tmp_path / "bin"
    folder.mkdir()
    script = folder / "journalctl"
    script.write_text(f"#!/usr/bin/env python3\nimport sys, time\n{body}\n")
    script.chmod(script.stat().st_mode | stat.S_IXUSR)
    monkeypatch.setenv("PATH", f"{folder}{os.pathsep}{os.environ.get('PATH', '')}")


def test_lines_are_bounded_and_an_over_long_one_is_dropped_whole(tmp_path, monkeypatch):
    monkeypatch.setattr(journalctl_module, "MAX_LINE_BYTES", 1000)
    fake_journalctl(
        tmp_path,
        monkeypatch,
        "out = sys.stdout.buffer\n"
        "out.write(b'first\\n' + b'x' * 5000)\nout.flush(); time.sleep(0.2)\n"
        "out.write(b'y' * 5000 + b'\\nsecond\\n' + b'z' * 999 + b'\\nlast')\n"
        "sys.stderr.write('Hint: not seeing other users\\n')",
    )
    process = Journalctl(JournalQuery())
    try:
        lines = [line for line in process.lines() if line is not None]
    finally:
        process.close()
    assert lines == [b"first", b"second", b"z" * 999, b"last"]
    assert process.too_long == 1 and list(process.stderr) == ["Hint: not seeing other users"]
    assert process.problem() == ""


def test_a_pause_is_said_and_close_ends_it(tmp_path, monkeypatch):
    fake_journalctl(tmp_path, monkeypatch, "print('one', flush=True)\ntime.sleep(60)")
    process = Journalctl(JournalQuery(follow=True))
    lines = process.lines(0.05)
    assert next(line for line in lines if line is not None) == b"one"
    assert next(lines) is None, "nothing came for a while"
    started = time.monotonic()
    process.close()
    assert process.exit_status() is not None and time.monotonic() - started < 5


def test_a_failing_journalctl_says_why(tmp_path, monkeypatch):
    fake_journalctl(tmp_path, monkeypatch, "sys.stderr.write('Failed to parse timestamp: garbage\\n'); sys.exit(1)")
    process = Journalctl(JournalQuery(since="garbage"))
    assert [line for line in process.lines() if line is not None] == []
    assert process.problem() == "journalctl failed (exit status 1): Failed to parse timestamp: garbage"
    process.close()


def test_without_journalctl_it_says_what_to_install(tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setattr(os, "access", lambda *_args: False)
    with pytest.raises(JournalUnavailable, match=r"journalctl is not installed .*package systemd"):
        find_journalctl()
