"""A kept history (``--keep-history``): sessions kept in the ROS log directory, pruned to a
bound oldest first, and read again (``--history``) as they were."""

from __future__ import annotations

import pytest

from console_tui.cli import main as cli_main
from console_tui.model.store.history_dir import close_spill, kept_sessions, open_kept_spill
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.spill_file import SpillFiles
from console_tui.ros.log_dir import KEPT_HISTORY
from console_tui.sources.files import open_log_file
from console_tui.sources.files.folders import expand_paths


def record(i: int) -> LogRecord:
    return LogRecord(
        1_700_000_000_000_000_000 + i * 1000,
        (10, 20, 30, 40, 50)[i % 5],
        f"node{i % 3}",
        f"message {i}" + ("\0with NUL" if i == 7 else ""),
        f"f{i % 4}.cpp",
        "fn",
        i % 100,
        "/rosout",
        topics="/a" if i % 11 == 0 else "",
        robot="arm" if i % 13 == 0 else "",
    )


def keep_session(base, first: int, count: int, bound: int = 1 << 30) -> None:
    spill, directory, why = open_kept_spill(base)
    assert spill is not None and directory is not None, why
    spill.files.segment_bytes = 300_000  # several segments a session
    store = LogStore(spill=spill)
    store.extend_records(record(i) for i in range(first, first + count))
    store.keep_rest()
    close_spill(spill, directory, bound=bound)


def read(base) -> list[LogRecord]:
    history = open_log_file(base)
    records = [record for batch in history.batches() for record in batch]
    assert not list(history.problems)
    return records


def test_a_kept_session_reads_back_as_it_was(tmp_path):
    base = tmp_path / KEPT_HISTORY
    count = 2 * CHUNK_SIZE + 100  # the last records were not a full chunk when it ended
    keep_session(base, 0, count)
    assert [
        (r.stamp_ns, r.level, r.node, r.msg, r.file, r.function, r.line, r.source, r.topics, r.robot)
        for r in read(base)
    ] == [
        (r.stamp_ns, r.level, r.node, r.msg, r.file, r.function, r.line, r.source, r.topics, r.robot)
        for r in (record(i) for i in range(count))
    ]


def test_sessions_read_oldest_first_and_the_bound_drops_the_oldest(tmp_path):
    base = tmp_path / KEPT_HISTORY
    keep_session(base, 0, 3 * CHUNK_SIZE)
    keep_session(base, 100_000, 3 * CHUNK_SIZE)
    messages = [r.msg for r in read(base)]
    assert messages[0] == "message 0" and messages[-1] == f"message {100_000 + 3 * CHUNK_SIZE - 1}"
    keep_session(base, 200_000, 3 * CHUNK_SIZE, bound=200_000)
    sessions = kept_sessions(base)
    assert sum(path.stat().st_size for session in sessions for path in session.iterdir()) <= 200_000
    kept = [r.msg for r in read(base)]
    assert kept[-1] == f"message {200_000 + 3 * CHUNK_SIZE - 1}" and kept[0] != "message 0"


def test_a_segment_cut_off_gives_what_came_before(tmp_path):
    base = tmp_path / KEPT_HISTORY
    keep_session(base, 0, 2 * CHUNK_SIZE)
    (session,) = kept_sessions(base)
    last = sorted(session.iterdir())[-1]
    data = last.read_bytes()
    last.write_bytes(data[: len(data) // 2])
    records = read(base)
    assert 0 < len(records) < 2 * CHUNK_SIZE and records[0].msg == "message 0"


def test_opening_the_log_directory_leaves_the_kept_history_out(tmp_path):
    log_dir = tmp_path / "log"
    keep_session(log_dir / KEPT_HISTORY, 0, CHUNK_SIZE + 1)
    (log_dir / "talker_1_1700000000000.log").write_text("[INFO] [1.000000000] [talker]: hi\n")
    assert [log.name for log in expand_paths([log_dir]).logs] == ["talker_1_1700000000000.log"]


def test_history_needs_a_kept_history_and_not_keeping_it_again(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path))
    with pytest.raises(SystemExit):
        cli_main(["--history"])
    assert "no kept history in" in capsys.readouterr().err
    (tmp_path / KEPT_HISTORY).mkdir()
    with pytest.raises(SystemExit):
        cli_main(["--history", "--keep-history"])
    assert "would keep it twice" in capsys.readouterr().err


def test_spill_files_begin_a_segment_with_every_string(tmp_path):
    files = SpillFiles(tmp_path, segment_bytes=1, min_free_bytes=0)
    files.make_room(10)
    files.make_room(10)
    assert files.segments() == [1]  # the first went empty: removed


def test_keep_history_as_the_command_does_keeps_the_session_for_history(tmp_path, monkeypatch):
    """``console-tui --keep-history``'s store: on disk, bounded by ``--max-messages``; at the
    end its records, the newest chunk too, are in the ROS log directory's kept history."""
    import argparse

    from console_tui.run_app import _history_store

    monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path))
    cleanups: list = []
    args = argparse.Namespace(max_messages=3 * CHUNK_SIZE + 10, keep_history=True, history_size=100)
    store = _history_store(args, cleanups)
    assert store.spill is not None and store.max_messages == 3 * CHUNK_SIZE + 10 and not store.memory_reason
    store.extend_records(record(i) for i in range(4 * CHUNK_SIZE + 10))
    assert store.first_seq == CHUNK_SIZE  # the oldest chunk gone at the bound
    for cleanup in cleanups:
        cleanup()
    assert len(kept_sessions(tmp_path / KEPT_HISTORY)) == 1
    kept = read(tmp_path / KEPT_HISTORY)
    assert [rec.msg for rec in kept] == [record(i).msg for i in range(CHUNK_SIZE, 4 * CHUNK_SIZE + 10)]
