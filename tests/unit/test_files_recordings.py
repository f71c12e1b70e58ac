"""Recordings (rosbag2 MCAP and sqlite3 written with rosbags, ROS 1 bags), merging,
background loading, and damaged recordings."""

from __future__ import annotations

import random
import threading

import pytest

pytest.importorskip("rosbags")
pytest.importorskip("mcap")

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
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


def _edit_metadata(bag, edit) -> None:
    from ruamel.yaml import YAML

    path = bag / "metadata.yaml"
    document = YAML(typ="safe").load(path.read_text())
    edit(document["rosbag2_bagfile_information"])
    with open(path, "w") as out:
        YAML().dump(document, out)


def test_sqlite3_directory_and_its_db3_give_the_same_records(tmp_path):
    """Issue 11, item 8: the directory gave 0 records and no word when its metadata.yaml
    described the topics otherwise than the .db3 (order, QoS profiles, type hashes)."""
    bag = write_rosbag2(tmp_path / "bag", hostile_records(), storage="sqlite3")
    never = "\n    sec: 2147483647\n    nsec: 4294967295"
    qos = (  # as rosbag2 (Humble) writes a publisher's QoS into metadata.yaml
        "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 1\n"
        f"  deadline:{never}\n  lifespan:{never}\n  liveliness: 1\n"
        f"  liveliness_lease_duration:{never}\n  avoid_ros_namespace_conventions: false\n"
    )

    def differ(info) -> None:
        info["topics_with_message_count"].reverse()
        for topic in info["topics_with_message_count"]:
            topic["topic_metadata"]["offered_qos_profiles"] = qos
            topic["topic_metadata"]["type_description_hash"] = "RIHS01_" + "0" * 64

    _edit_metadata(bag, differ)
    from_directory, directory = _read(bag)
    from_db3, _ = _read(next(bag.glob("*.db3")))
    assert len(from_directory) == len(hostile_records()) and list(directory.problems) == []
    assert [fields(r)[:-1] for r in from_directory] == [fields(r)[:-1] for r in from_db3]


def test_an_empty_recording_always_says_why(tmp_path):
    quiet = write_rosbag2(tmp_path / "quiet", hostile_records(), storage="sqlite3", log_topics=())
    files = [open_log_file(quiet)]
    assert [r for batch in load_records(files) for r in batch] == []
    (problem,) = files[0].problems
    assert problem.what == (
        "no log messages: no log topic (rcl_interfaces/msg/Log, rosgraph_msgs/Log) was recorded, only /chatter"
    )

    def promise(info) -> None:
        entry = {**info["topics_with_message_count"][0]}
        entry["topic_metadata"] = {**entry["topic_metadata"], "name": "/rosout", "type": "rcl_interfaces/msg/Log"}
        info["topics_with_message_count"].append(entry)

    _edit_metadata(quiet, promise)
    files = [open_log_file(quiet)]
    assert [r for batch in load_records(files) for r in batch] == []
    assert [p.what for p in files[0].problems] == [
        "metadata.yaml lists log messages on /rosout, but the recording's files hold no such topic"
    ]


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
        ("half.db3", b"SQLite format 3\x00" + bytes(200), "cannot read this rosbag2 recording"),
    ],
    ids=["empty", "text", "garbage", "half-db3"],
)
def test_broken_recordings_say_what_is_wrong(tmp_path, name, content, message):
    path = tmp_path / name
    path.write_bytes(content)
    with pytest.raises(FormatError) as caught:
        open_log_file(path)
    assert message in str(caught.value) and str(caught.value).startswith(name)


def test_unindexed_ros1_bag_is_read_from_the_start_and_says_to_reindex(tmp_path):
    bag = write_ros1_bag(tmp_path / "r.bag", hostile_records())
    data = bytearray(bag.read_bytes())
    index_pos = data.find(b"index_pos=") + len("index_pos=")
    data[index_pos : index_pos + 8] = bytes(8)  # what an interrupted 'rosbag record' leaves
    active = tmp_path / "r.bag.active"
    active.write_bytes(bytes(data))
    records, log_file = _read(active)
    assert [fields(r) for r in records] == _expected("r.bag.active")
    (problem,) = log_file.problems
    assert "no index" in problem.what and "rosbag reindex" in problem.what and log_file.topics == ["/rosout"]


@pytest.mark.parametrize("compression", ["", "lz4"])
def test_ros1_bag_with_a_damaged_index_keeps_what_can_be_read(tmp_path, compression):
    """Issue 11, item 9: an index the library rejects ended 'convert' with an
    AssertionError traceback and the app with 'loading stopped: AssertionError:'."""
    bag = write_ros1_bag(tmp_path / "r.bag", hostile_records() * 50, compression=compression)
    data = bytearray(bag.read_bytes())
    index_data = data.find(b"\x04\x00\x00\x00op=\x04") - 4  # the first index record after a chunk
    assert index_data > 0 and data[index_data : index_data + 4] == (47).to_bytes(4, "little")
    data[index_data : index_data + 4] = (48).to_bytes(4, "little")
    damaged = tmp_path / "damaged.bag"
    damaged.write_bytes(bytes(data))
    records, log_file = _read(damaged)
    assert [fields(r) for r in records] == [fields(r) for r in hostile_records("damaged.bag") * 50]
    first, where = log_file.problems  # why the index went unused, then where the damage is
    assert first.what.startswith("its index is damaged (AssertionError (a check of the reading library failed")
    assert "read record by record from the start instead" in first.what
    assert index_data <= where.offset < index_data + 200 and "what came before it was read" in where.what
    if compression:
        return  # one compressed chunk: cut, it holds nothing readable
    cut = tmp_path / "cut.bag"
    cut.write_bytes(bytes(data[: len(data) // 2]))
    records, log_file = _read(cut)
    assert 0 < len(records) < len(hostile_records()) * 50
    assert [fields(r) for r in records] == [fields(r) for r in (hostile_records("cut.bag") * 50)[: len(records)]]
    assert "what came before it was read" in log_file.problems.items[-1].what


def test_convert_and_the_loader_name_the_damaged_bag(tmp_path, capsys):
    from console_tui.cli import main

    bag = write_ros1_bag(tmp_path / "r.bag", hostile_records())
    data = bytearray(bag.read_bytes())
    index_data = data.find(b"\x04\x00\x00\x00op=\x04") - 4
    data[index_data : index_data + 4] = (48).to_bytes(4, "little")
    (tmp_path / "r.bag").write_bytes(bytes(data))
    assert main(["convert", str(tmp_path / "r.bag"), "-o", str(tmp_path / "out.jsonl")]) == 1
    err = capsys.readouterr().err
    assert "r.bag: its index is damaged (AssertionError" in err and "Traceback" not in err
    assert len((tmp_path / "out.jsonl").read_text().split("\n")) == len(hostile_records()) + 1
    garbage = tmp_path / "half.bag"
    garbage.write_bytes(b"#ROSBAG V2.0\n" + random.Random(8).randbytes(100))
    queue = IntakeQueue()
    load = FileLoad([garbage], queue)
    load.start()
    assert load.join(30)
    problems = [str(p) for p in load.problems()]
    assert problems[0].startswith("half.bag: its index is damaged") and len(problems) == 2
    assert "what came before it was read" in problems[1] and not load.error


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
