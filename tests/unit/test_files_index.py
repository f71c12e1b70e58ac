"""Big text logs read by index: the records the store gives are the ones reading the file whole
gives, whatever the format, whether the scanner in C or the format's reader read them, and a
file that grows or gets shorter while (or after) it is read is handled and said."""

from __future__ import annotations

import io
import os
import random
import threading
import time
from itertools import accumulate
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from console_tui.model.formats import Problems, TextLines
from console_tui.model.formats.rcutils_log import RcutilsLogFormat
from console_tui.model.formats.rosout_log import ROS2_HEADER, rosout_log_text
from console_tui.model.formats.save import save_records
from console_tui.model.store.chunk_spill import ChunkSpill
from console_tui.model.store.indexed_chunk import IndexedChunk
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.spill_file import SpillFiles
from console_tui.sources.files import FileLoad, compiled_scan, open_log_file

SCANNER, _NOTE = compiled_scan.load()
SCAN = SCANNER.scan if SCANNER is not None else None
needs_scan = pytest.mark.skipif(SCANNER is None, reason=f"no scanner in C here: {_NOTE}")
LEVELS = ("DEBUG", "INFO", "WARN", "ERROR", "FATAL", "UNSET")


def rcutils_line(i: int, rng: random.Random, odd: float = 0.0) -> str:
    """A node's log line (a message on several lines now and then); ``odd`` of them are lines
    the scanner leaves to the Python reader (colour, a stray line, a bad stamp)."""
    text = f"message {i} " + rng.choice(["", "é", "日本", "a]: b", "[x] [y]", "tab\there"])
    if i % 97 == 0:
        text += "\n  a second line\n\n  after a blank one"
    line = f"[{LEVELS[i % 6]}] [{1_700_000_000 + i // 1000}.{i % 1000:09d}] [node.{i % 7}]: {text}\n"
    if rng.random() < odd:
        line = rng.choice(
            [
                f"\x1b[33m{line[:-1]}\x1b[0m\n",  # colour codes
                "stray text that is no record\n" + line,
                f"[INFO] [{i}] [bad.stamp]: the stamp has no nanoseconds\n",
                f"[INFO] [1.000000000] [no.colon] {text}\n",
                line.replace("message", "mes\x00sage"),
            ]
        )
    return line


def write(path: Path, lines: list[str], head: str = "") -> Path:
    path.write_text(head + "".join(lines), encoding="utf-8", errors="surrogateescape")
    return path


def indexed_store(path: Path, tmp_path: Path, *, scan: bool = True) -> tuple[LogStore, FileLoad]:
    """The store a file read by index gives (its chunks on disk), and the load."""
    queue = IntakeQueue()
    directory = tmp_path / f"spill-{time.monotonic_ns()}"
    directory.mkdir()
    store = LogStore(spill=ChunkSpill(SpillFiles(directory, min_free_bytes=0), warm_chunks=2))
    load = FileLoad([path], queue, index_from_bytes=0)
    saved = compiled_scan._loaded
    if not scan:
        compiled_scan._loaded = (None, "off for this test")
    try:
        load.start()
        while not load.finished or len(queue):
            drain(queue, store)
            time.sleep(0.005)
    finally:
        compiled_scan._loaded = saved
    assert load.indexed
    return store, load


def drain(queue: IntakeQueue, store: LogStore) -> None:
    for batch in queue.drain_batches():
        if isinstance(batch, IndexedChunk):
            store.extend_indexed(batch)
        else:
            store.extend(batch)


def whole_store(path: Path) -> tuple[LogStore, list[str]]:
    """The file's records in its order (reading it whole sorts them a little by stamp: an
    index keeps the file's order), and its problems."""
    file = open_log_file(path)
    store = LogStore()
    for batch in file.batches():
        store.extend_records(batch)
    return store, [str(problem) for problem in file.problems]


def same_records(indexed: LogStore, whole: LogStore) -> None:
    assert len(indexed) == len(whole)
    assert indexed.counts == whole.counts
    for seq in range(len(whole)):
        assert indexed.get(seq) == whole.get(seq), seq


@pytest.mark.parametrize("scan", [pytest.param(True, marks=needs_scan), False], ids=["c", "python"])
def test_a_node_log_read_by_index_gives_what_reading_it_whole_gives(tmp_path, scan):
    rng = random.Random(7)
    path = write(tmp_path / "node.log", [rcutils_line(i, rng, odd=0.002) for i in range(3 * CHUNK_SIZE + 123)])
    store, load = indexed_store(path, tmp_path, scan=scan)
    whole, problems = whole_store(path)
    same_records(store, whole)
    assert store.on_disk == 3 * CHUNK_SIZE  # the last part was read whole
    assert [str(p) for p in load.problems()] == problems


def test_rosout_csv_and_json_lines_are_read_by_index_too(tmp_path):
    records = [
        LogRecord(
            1_700_000_000_000_000_000 + i * 1_000_003,
            (10, 20, 30, 40, 50)[i % 5],
            f"/node{i % 5}",
            f"message {i}" + ("\nsecond line" if i % 50 == 0 else ""),
            f"f{i % 3}.cpp",
            f"fn{i % 4}",
            i % 300,
        )
        for i in range(2 * CHUNK_SIZE + 77)
    ]
    rosout = tmp_path / "rosout.log"
    rosout.write_text(ROS2_HEADER + "".join(rosout_log_text(record) for record in records))
    for path in (rosout, tmp_path / "saved.csv", tmp_path / "saved.jsonl"):
        if path.suffix != ".log":
            save_records(records, path)
        store, _load = indexed_store(path, tmp_path)
        whole, _ = whole_store(path)
        same_records(store, whole)
        assert store.on_disk == 2 * CHUNK_SIZE, path.name


@needs_scan
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    st.lists(
        st.sampled_from(
            [
                "[INFO] [1.000000001] [a]: x",
                "[WARN] [-5.000000000] [b]: y ]: z",
                "  more",
                "",
                "[INFO] [1.5] [c]: bad",
                "[ERROR] [2.000000000] [d]:",
                "\x1b[0m",
                "[DEBUG] [3.000000000] [é]: ✓",
                "[INFO] [1٣.000000000] [u]: digits",
                "\r",
                "[FATAL] [99999999999.000000000] [big]: big",
                "[INFO] [4.000000000] [e]: \udcff",
            ]
        ),
        min_size=1,
        max_size=12,
    ),
    st.booleans(),
)
def test_the_scanner_reads_what_the_python_reader_reads_or_leaves_it(lines, final_newline):
    data = ("\n".join(lines) + ("\n" if final_newline else "")).encode("utf-8", "surrogatepass")
    status, stop, count, _lines, stamps, levels, _ids, messages, starts = SCAN(
        data, 0, len(data), 100, {}, [], True, True
    )
    if status == 2:
        data = data[:stop]  # the records before the line it leaves
    text_format = RcutilsLogFormat()
    problems = Problems("t")
    expected = list(text_format.records(TextLines(io.BytesIO(data), problems), "t", problems))
    assert count == len(expected)
    got = messages.decode("utf-8").split("\0") if count else []
    assert got == [record.msg for record in expected]
    assert list(memoryview(stamps).cast("q")) == [record.stamp_ns for record in expected]
    assert list(levels) == [record.level for record in expected]
    assert list(memoryview(starts).cast("I")) == list(accumulate((len(m) + 1 for m in got), initial=0))


def test_a_file_that_grows_while_it_is_read_is_read_to_its_new_end(tmp_path):
    rng = random.Random(3)
    path = write(tmp_path / "growing.log", [rcutils_line(i, rng) for i in range(2 * CHUNK_SIZE)])
    queue = IntakeQueue()
    grown = threading.Event()

    def sink(batch) -> None:
        queue.put(batch)
        if not grown.is_set():
            grown.set()
            with open(path, "a", encoding="utf-8") as out:
                out.write("".join(rcutils_line(i, rng) for i in range(2 * CHUNK_SIZE, 3 * CHUNK_SIZE + 5)))

    load = FileLoad([path], sink, index_from_bytes=0)
    load.start()
    load.join(30)
    store = LogStore(spill=ChunkSpill(SpillFiles(tmp_path, min_free_bytes=0)))
    drain(queue, store)
    assert len(store) == 3 * CHUNK_SIZE + 5
    assert store.get(len(store) - 1).msg.startswith(f"message {3 * CHUNK_SIZE + 4} ")


def test_a_file_cut_short_after_it_was_read_shows_placeholders_and_says_so(tmp_path):
    rng = random.Random(5)
    path = write(tmp_path / "cut.log", [rcutils_line(i, rng) for i in range(3 * CHUNK_SIZE)])
    store, _load = indexed_store(path, tmp_path)
    assert store.spill is not None
    store.spill._warm.clear()
    os.truncate(path, 1000)
    assert store.get(2 * CHUNK_SIZE).msg.startswith("(no longer in cut.log")
    assert "cut.log changed after it was read" in store.spill.read_problem


def test_a_file_cut_short_while_it_is_read_is_said(tmp_path):
    rng = random.Random(6)
    path = write(tmp_path / "shrinking.log", [rcutils_line(i, rng) for i in range(3 * CHUNK_SIZE)])
    queue = IntakeQueue()
    cut = threading.Event()

    def sink(batch) -> None:
        queue.put(batch)
        if not cut.is_set():
            cut.set()
            os.truncate(path, 100)

    load = FileLoad([path], sink, index_from_bytes=0)
    load.start()
    assert load.join(30)
    assert any("got shorter while it was read" in str(problem) for problem in load.problems())


@needs_scan
def test_a_search_reads_only_the_messages_of_chunks_whose_bytes_hold_the_text(tmp_path):
    from console_tui.model.view.log_view import LogView
    from console_tui.model.view.search_walk import Search, parse_search

    rng = random.Random(8)
    lines = [rcutils_line(i, rng) for i in range(4 * CHUNK_SIZE)]
    lines[CHUNK_SIZE + 5] = lines[CHUNK_SIZE + 5].replace("message", "Needle message")
    store, _load = indexed_store(write(tmp_path / "search.log", lines), tmp_path)
    assert store.spill is not None
    store.spill._warm.clear()
    read = []
    for source in store.spill.text_sources.values():
        load = source.load
        source.load = lambda texts, stamps, load=load: read.append(texts.start) or load(texts, stamps)  # type: ignore[method-assign]
    search = Search(LogView(store), parse_search("Needle"), store.end_seq)
    while not search.step(1.0):
        pass
    assert list(search.seqs()) == [CHUNK_SIZE + 5]
    assert len(read) == 1  # one chunk's messages read, not four


@needs_scan
@settings(max_examples=300, deadline=None)
@given(st.binary(max_size=200), st.binary(min_size=0, max_size=6).map(lambda b: b.lower()), st.booleans())
def test_contains_is_bytes_in(data, needle, ignore_case):
    assert SCANNER is not None
    if ignore_case:
        if not (data.isascii() and needle.isascii()):
            return
        assert SCANNER.contains(data, needle, True) == (needle in data.lower())
    else:
        assert SCANNER.contains(data, needle, False) == (needle in data)
