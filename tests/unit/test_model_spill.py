"""The store's full chunks on disk: read back as they were, dropped with their files, and a
disk that fails (full, a size limit, damaged files) said and survived, never raised."""

from __future__ import annotations

import errno
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from console_tui.model.store.chunk_spill import ChunkSpill
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.model.store.spill_file import SpillFiles


def record(i: int) -> LogRecord:
    return LogRecord(
        stamp_ns=1_700_000_000_000_000_000 + 1000 * i,
        level=(10, 20, 20, 30, 40, 50)[i % 6],
        node=f"node{i % 7}",
        msg=f"message {i} " + "é" * (i % 3),
        file=f"file{i % 5}.cpp",
        function=f"fn{i % 11}",
        line=i % 70_000,  # wider than 2 bytes now and then
        source="/rosout",
        topics="/a,/b" if i % 13 == 0 else "",
        robot="picker" if i % 17 == 0 else "",
    )


def spilled_store(path: Path, max_messages: int = 50 * CHUNK_SIZE, **options: object) -> LogStore:
    files = SpillFiles(path, segment_bytes=options.pop("segment_bytes", 1 << 20), min_free_bytes=0)  # type: ignore[arg-type]
    return LogStore(max_messages, spill=ChunkSpill(files, warm_chunks=2, **options), memory_bound=3 * CHUNK_SIZE)  # type: ignore[arg-type]


def fill(store: LogStore, count: int, start: int = 0, batch: int = 1000) -> None:
    for first in range(start, start + count, batch):
        store.extend(RecordColumns.from_records([record(i) for i in range(first, min(first + batch, start + count))]))


def test_spilled_chunks_read_back_as_they_were(tmp_path):
    store, reference = spilled_store(tmp_path), LogStore()
    fill(store, 5 * CHUNK_SIZE + 100)
    fill(reference, 5 * CHUNK_SIZE + 100)
    assert store.on_disk == 5 * CHUNK_SIZE
    assert store.spill is not None and store.spill.warm_count <= 2
    for seq in range(0, store.end_seq, 997):
        assert store.get(seq) == reference.get(seq)
    columns, expected = store.columns(100, 4 * CHUNK_SIZE + 50), reference.columns(100, 4 * CHUNK_SIZE + 50)
    assert columns.records() == expected.records()
    assert store.counts == reference.counts


def test_messages_that_hold_nul_are_kept_too(tmp_path):
    store = spilled_store(tmp_path)
    store.extend(RecordColumns.from_records([LogRecord(i, 20, "n", f"a\0{i}") for i in range(CHUNK_SIZE + 1)]))
    assert store.on_disk == CHUNK_SIZE
    store.spill._warm.clear()  # type: ignore[union-attr]
    assert store.get(5).msg == "a\x005"


def test_dropping_the_oldest_removes_their_files(tmp_path):
    store = spilled_store(tmp_path, max_messages=4 * CHUNK_SIZE, segment_bytes=CHUNK_SIZE * 40)
    fill(store, 40 * CHUNK_SIZE)
    assert len(store) == 4 * CHUNK_SIZE
    assert len(list(tmp_path.iterdir())) <= 3
    assert store.get(store.first_seq).msg.startswith(f"message {store.first_seq} ")
    assert store.evicted == 36 * CHUNK_SIZE


def test_records_on_disk_go_a_whole_chunk_at_a_time_never_beyond_the_bound(tmp_path):
    """Part of a chunk on disk would be read back only to count what goes: the oldest chunk
    goes whole, once the bound reaches into it."""
    store = spilled_store(tmp_path, max_messages=4 * CHUNK_SIZE + 100)
    fill(store, 4 * CHUNK_SIZE + 100)
    assert store.evicted == 0
    fill(store, 1, start=store.end_seq)  # one more than the bound: the oldest chunk goes whole
    assert (store.first_seq, len(store)) == (CHUNK_SIZE, 3 * CHUNK_SIZE + 101)
    fill(store, CHUNK_SIZE - 1, start=store.end_seq)  # still within the bound
    assert (store.first_seq, len(store)) == (CHUNK_SIZE, 4 * CHUNK_SIZE + 100)
    kept = [record(seq).level for seq in range(store.first_seq, store.end_seq)]
    assert store.evicted == CHUNK_SIZE and store.counts == {level: kept.count(level) for level in store.counts}


def test_a_full_disk_keeps_chunks_in_memory_bounded_and_says_so(tmp_path):
    failing = {"on": False}

    def write(fd: int, data: bytes) -> int:
        if failing["on"]:
            raise OSError(errno.ENOSPC, "No space left on device")
        return os.write(fd, data)

    now = [0.0]
    files = SpillFiles(tmp_path, segment_bytes=1 << 20, min_free_bytes=0, write=write)
    store = LogStore(spill=ChunkSpill(files, warm_chunks=2, clock=lambda: now[0]), memory_bound=3 * CHUNK_SIZE)
    fill(store, 2 * CHUNK_SIZE)
    failing["on"] = True
    fill(store, 2 * CHUNK_SIZE, start=2 * CHUNK_SIZE)
    assert "No space left" in store.spill_problem
    assert store.on_disk == 2 * CHUNK_SIZE and len(store) == 4 * CHUNK_SIZE
    fill(store, 4 * CHUNK_SIZE, start=4 * CHUNK_SIZE)  # memory holds the newest 3 chunks' worth
    assert len(store) == 3 * CHUNK_SIZE and store.on_disk == 0
    assert [r.msg.split()[1] for r in store.records(store.first_seq, store.first_seq + 2)] == [
        str(store.first_seq),
        str(store.first_seq + 1),
    ]
    failing["on"] = False
    now[0] = 100.0  # time to try again: the full chunks go to disk
    fill(store, CHUNK_SIZE, start=8 * CHUNK_SIZE)
    assert store.spill_problem == "" and store.on_disk >= 2 * CHUNK_SIZE
    assert store.get(store.first_seq).msg.startswith(f"message {store.first_seq} ")


def test_a_rewrite_of_the_newest_records_reaches_into_chunks_on_disk(tmp_path):
    store = spilled_store(tmp_path)
    fill(store, 3 * CHUNK_SIZE + 10)
    start = 2 * CHUNK_SIZE - 5
    kept = store.columns(start, store.end_seq).records()
    store.rewrite_from(start, RecordColumns.from_records(list(reversed(kept))))
    assert store.get(start).msg == kept[-1].msg and store.get(store.end_seq - 1).msg == kept[0].msg
    fill(store, 2 * CHUNK_SIZE, start=10_000)
    assert store.get(start + 1).msg == kept[-2].msg


def test_a_damaged_history_file_reads_as_placeholders_not_an_error(tmp_path):
    store = spilled_store(tmp_path)
    fill(store, 3 * CHUNK_SIZE)
    store.spill._warm.clear()  # type: ignore[union-attr]
    for segment in tmp_path.iterdir():
        os.truncate(segment, 100)
    found = store.get(10)
    assert found.msg.startswith("(lost: a chunk of the history on disk cannot be read")
    assert "cannot be read" in store.spill_problem


def test_clear_removes_the_files(tmp_path):
    store = spilled_store(tmp_path, segment_bytes=CHUNK_SIZE * 20)
    fill(store, 12 * CHUNK_SIZE)
    store.clear()
    fill(store, 100, start=99_000)
    assert len(list(tmp_path.iterdir())) <= 1 and len(store) == 100


@pytest.mark.skipif(sys.platform != "linux", reason="RLIMIT_FSIZE as Linux has it")
def test_a_file_size_limit_is_a_full_disk_too(tmp_path):
    """The kernel's own refusal (EFBIG, with SIGXFSZ ignored as Python does), in a process of its own."""
    script = textwrap.dedent(
        f"""
        import resource
        from pathlib import Path
        from console_tui.model.store.chunk_spill import ChunkSpill
        from console_tui.model.store.record import LogRecord
        from console_tui.model.store.record_batch import RecordColumns
        from console_tui.model.store.spill_file import SpillFiles
        from console_tui.model.store.log_store import LogStore
        resource.setrlimit(resource.RLIMIT_FSIZE, (300_000, 300_000))
        store = LogStore(spill=ChunkSpill(SpillFiles(Path({str(tmp_path)!r}), min_free_bytes=0)), memory_bound=50_000)
        for start in range(0, 40_000, 1000):
            store.extend(RecordColumns.from_records([LogRecord(i, 20, "n", f"message {{i}} " * 8) for i in range(start, start + 1000)]))
        print(len(store), store.on_disk > 0, store.spill_problem)
        """
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    count, some_on_disk, problem = done.stdout.strip().split(" ", 2)
    assert int(count) == 40_000 and some_on_disk == "True" and "too large" in problem.lower()
