"""Recordings (rosbag2 MCAP and sqlite3 written with rosbags, ROS 1 bags), merging,
background loading, and damaged recordings."""

from __future__ import annotations

import random
import threading

import pytest

pytest.importorskip("rosbags")
pytest.importorskip("mcap")

from console_tui.model.intake_queue import IntakeQueue
from console_tui.model.record import LogRecord
from console_tui.sources.files import FileLoad, FormatError, load_records, open_log_file

from support.formats import fields, hostile_records
from support.recordings import write_ros1_bag, write_rosbag2


def _read(path, **kwargs) -> tuple[list[LogRecord], object]:
    log_file = open_log_file(path, **kwargs)
    records = [r for batch in log_file.batches() for r in batch]
    return records, log_file


def _expected(source: str) -> list[tuple]:
    return [fields(r) for r in hostile_records(source)]


@pytest.mark.parametrize("storage", ["mcap", "sqlite3"])
def test_rosbag2_log_messages_come_back_exactly(tmp_path, storage):
    bag = write_rosbag2(tmp_path / "run", hostile_records(), storage=storage, image_bytes=50_000, images_per_log=1)
    records, log_file = _read(bag)
    assert [fields(r) for r in records] == _expected("run")
    assert log_file.topics == ["/rosout"] and list(log_file.problems) == [] and log_file.fraction == 1.0
    storage_file = next(p for p in bag.iterdir() if p.suffix in (".mcap", ".db3"))
    records, _ = _read(storage_file)
    assert [fields(r) for r in records] == _expected(storage_file.name)
    records, _ = _read(bag / "metadata.yaml")
    assert len(records) == len(hostile_records())


@pytest.mark.parametrize("compress", ["message", "storage"])
def test_compressed_rosbag2(tmp_path, compress):
    bag = write_rosbag2(tmp_path / "z", hostile_records(), storage="mcap", compress=compress)
    records, _ = _read(bag)
    assert [fields(r) for r in records] == _expected("z")
    if compress == "storage":  # the .mcap alone: zstd chunks read whole
        records, _ = _read(next(bag.glob("*.mcap")))
        assert len(records) == len(hostile_records())


def test_rosout_agg_is_read_instead_of_rosout_when_both_were_recorded(tmp_path):
    bag = write_rosbag2(tmp_path / "both", hostile_records(), log_topics=("/rosout", "/rosout_agg"))
    records, log_file = _read(bag)
    assert log_file.topics == ["/rosout_agg"] and len(records) == len(hostile_records())


def test_a_recording_without_log_topics_is_empty_not_an_error(tmp_path):
    bag = write_rosbag2(tmp_path / "quiet", hostile_records(), storage="sqlite3", log_topics=())
    records, log_file = _read(bag)
    assert records == [] and log_file.topics == []


def test_large_images_are_not_read(tmp_path):
    bag = write_rosbag2(tmp_path / "img", hostile_records() * 4, storage="mcap", image_bytes=400_000, images_per_log=1)
    mcap_file = next(bag.glob("*.mcap"))
    size = mcap_file.stat().st_size
    before = _bytes_read()
    records, _ = _read(mcap_file)
    read = _bytes_read() - before
    assert len(records) == 4 * len(hostile_records())
    assert size > 30_000_000
    assert read < size / 20, f"read {read} bytes of a {size}-byte recording"


def _bytes_read() -> int:
    with open("/proc/self/io") as stats:
        return int(next(line for line in stats if line.startswith("rchar:")).split()[1])


@pytest.mark.parametrize("compression", ["", "bz2", "lz4"])
def test_ros1_bag(tmp_path, compression):
    bag = write_ros1_bag(tmp_path / "r1.bag", hostile_records(), compression=compression)
    records, log_file = _read(bag)
    assert log_file.kind == "ros1-bag" and log_file.topics == ["/rosout"]
    assert [fields(r) for r in records] == _expected("r1.bag")


def test_truncated_mcap_gives_the_good_part_and_says_where(tmp_path):
    bag = write_rosbag2(tmp_path / "cut", hostile_records() * 200, storage="mcap", image_bytes=20_000, images_per_log=1)
    whole = next(bag.glob("*.mcap"))
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(whole.read_bytes()[: whole.stat().st_size * 6 // 10])
    records, log_file = _read(cut)
    problems = list(log_file.problems)
    assert 0 < len(records) < 200 * len(hostile_records())
    assert [fields(r) for r in records] == [fields(r) for r in (hostile_records("cut.mcap") * 200)[: len(records)]]
    assert "no usable index" in problems[0].what
    assert problems[-1].offset is not None and "ends early" in problems[-1].what


def test_damaged_log_message_in_an_indexed_mcap_is_reported_and_skipped(tmp_path):
    bag = write_rosbag2(tmp_path / "bad", hostile_records(), storage="mcap", chatter_every=0)
    path = next(bag.glob("*.mcap"))
    data = bytearray(path.read_bytes())
    marker = b"semi;colons;everywhere"
    at = data.find(marker)
    data[at - 4 : at] = b"\xff\xff\xff\x7f"  # the string's length, now absurd
    path.write_bytes(bytes(data))
    records, log_file = _read(path)
    assert len(records) == len(hostile_records()) - 1
    assert "cannot decode the log message" in log_file.problems.items[0].what


@pytest.mark.parametrize(
    "name, content, message",
    [
        ("empty.bag", b"", "the file is empty"),
        ("notes.bag", b"hello\n", "does not start like one"),
        ("garbage.mcap", random.Random(7).randbytes(5000), "does not start like one"),
        ("half.bag", b"#ROSBAG V2.0\n" + random.Random(8).randbytes(100), "cannot read this ROS 1 bag"),
        ("half.db3", b"SQLite format 3\x00" + bytes(200), "cannot read this rosbag2 recording"),
    ],
    ids=["empty", "text", "garbage", "half-bag", "half-db3"],
)
def test_broken_recordings_say_what_is_wrong(tmp_path, name, content, message):
    path = tmp_path / name
    path.write_bytes(content)
    with pytest.raises(FormatError) as caught:
        open_log_file(path)
    assert message in str(caught.value) and str(caught.value).startswith(name)


def test_unindexed_ros1_bag_says_to_reindex(tmp_path):
    bag = write_ros1_bag(tmp_path / "r.bag", hostile_records())
    data = bytearray(bag.read_bytes())
    index_pos = data.find(b"index_pos=") + len("index_pos=")
    data[index_pos : index_pos + 8] = bytes(8)  # what an interrupted 'rosbag record' leaves
    active = tmp_path / "r.bag.active"
    active.write_bytes(bytes(data))
    with pytest.raises(FormatError, match="rosbag reindex"):
        open_log_file(active)


def test_several_files_merge_by_time_each_keeping_its_source(tmp_path):
    early = [LogRecord(t, 20, "a", f"a{t}") for t in range(0, 100, 2)]
    write_rosbag2(tmp_path / "a", early)
    (tmp_path / "b.log").write_text("".join(f"[INFO] [0.{t:09d}] [b]: b{t}\n" for t in range(1, 100, 2)))
    files = [open_log_file(tmp_path / "a"), open_log_file(tmp_path / "b.log")]
    merged = [r for batch in load_records(files) for r in batch]
    assert [r.stamp_ns for r in merged] == list(range(100))
    assert {r.source for r in merged if r.node == "a"} == {"a"}
    assert {r.source for r in merged if r.node == "b"} == {"b.log"}


def test_same_file_names_get_told_apart(tmp_path):
    for run in ("run1", "run2"):
        (tmp_path / run).mkdir()
        (tmp_path / run / "rosout.log").write_text(f"1.000000000 INFO /n [f.py:1(f)] {run}\n")
    queue = IntakeQueue()
    load = FileLoad([tmp_path / "run1" / "rosout.log", tmp_path / "run2" / "rosout.log"], queue)
    load.start()
    assert load.join(30)
    assert sorted(r.source for r in queue.drain()) == ["run1/rosout.log", "run2/rosout.log"]


def test_background_load_reports_progress_and_problems(tmp_path):
    write_rosbag2(tmp_path / "ok", hostile_records())
    (tmp_path / "junk.log").write_bytes(b"\x00\x01binary")
    changes = []
    queue = IntakeQueue()
    load = FileLoad(
        [tmp_path / "ok", tmp_path / "junk.log", tmp_path / "missing.csv"], queue, on_change=lambda: changes.append(1)
    )
    load.start()
    assert load.join(30)
    progress = load.progress
    assert progress.finished and not progress.cancelled and progress.fraction == 1.0
    assert progress.records == len(hostile_records()) == len(queue.drain())
    assert [f.failed for f in progress.files] == [False, True, True]
    problems = [str(p) for p in load.problems()]
    assert problems[0].startswith("junk.log: binary data") and problems[1] == "missing.csv: no such file or directory"
    assert changes


def test_a_large_load_can_be_cancelled(tmp_path):
    big = tmp_path / "big.log"
    with open(big, "w") as out:
        for i in range(300_000):
            out.write(f"[INFO] [{1_700_000_000 + i}.000000000] [n]: message number {i}\n")
    first_batch = threading.Event()
    queue = IntakeQueue()
    load = FileLoad([big], lambda batch: (queue.put(batch), first_batch.set()))
    load.start()
    assert first_batch.wait(30)
    load.cancel()
    assert load.join(30)
    progress = load.progress
    assert progress.cancelled and progress.finished
    assert 0 < progress.records < 300_000
    assert progress.files[0].fraction < 1.0
