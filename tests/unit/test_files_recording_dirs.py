"""rosbag2 directories as people find them: split into several MCAP files, the metadata
missing or damaged, a bare folder. Each opens as far as it can, or says what is wrong."""

from __future__ import annotations

import shutil

import pytest

from console_tui.sources.files import FormatError, open_log_file

from support.formats import fields, hostile_records
from support.recordings import write_rosbag2


def read(path):
    log_file = open_log_file(path)
    return [r for batch in log_file.batches() for r in batch], log_file


def split_in_two(tmp_path):
    """One rosbag2 MCAP recording made of two files, as ``ros2 bag record --max-bag-size`` leaves."""
    first = write_rosbag2(tmp_path / "first", hostile_records()[:3], storage="mcap")
    second = write_rosbag2(tmp_path / "second", hostile_records()[3:], storage="mcap")
    run = tmp_path / "run"
    run.mkdir()
    shutil.copy(next(first.glob("*.mcap")), run / "run_0.mcap")
    shutil.copy(next(second.glob("*.mcap")), run / "run_1.mcap")
    metadata = (first / "metadata.yaml").read_text()
    name = next(first.glob("*.mcap")).name
    metadata = metadata.replace(f"- {name}", "- run_0.mcap\n  - run_1.mcap")
    (run / "metadata.yaml").write_text(metadata)
    return run


def test_a_split_mcap_recording_reads_its_files_in_order_as_one(tmp_path):
    run = split_in_two(tmp_path)
    records, log_file = read(run)
    assert [fields(r)[:4] for r in records] == [fields(r)[:4] for r in hostile_records()]
    assert log_file.kind == "mcap" and log_file.total == 2 and log_file.done == 2
    assert log_file.fraction == 1.0 and log_file.topics == ["/rosout"]
    assert list(log_file.problems) == []
    log_file.close()


def test_a_split_recording_stops_between_files_when_cancelled(tmp_path):
    import threading

    run = split_in_two(tmp_path)
    log_file = open_log_file(run)
    cancel = threading.Event()
    cancel.set()
    records = [r for batch in log_file.batches(cancel) for r in batch]
    assert records and len(records) < len(hostile_records()) and log_file.done == 1
    log_file.close()


def test_a_folder_with_one_mcap_file_and_no_metadata_is_read(tmp_path):
    bag = write_rosbag2(tmp_path / "bag", hostile_records(), storage="mcap")
    (bag / "metadata.yaml").unlink()
    records, _ = read(bag)
    assert len(records) == len(hostile_records())


def test_a_folder_without_metadata_or_mcap_says_it_is_no_recording(tmp_path):
    bag = write_rosbag2(tmp_path / "bag", hostile_records(), storage="sqlite3")
    (bag / "metadata.yaml").unlink()
    with pytest.raises(FormatError) as caught:
        open_log_file(bag)
    assert "bag: a directory, but not a rosbag2 recording (no metadata.yaml)" in str(caught.value)


def test_unreadable_metadata_is_named(tmp_path):
    bag = write_rosbag2(tmp_path / "bag", hostile_records(), storage="mcap")
    (bag / "metadata.yaml").write_text("rosbag2_bagfile_information: [unclosed\n")
    with pytest.raises(FormatError) as caught:
        open_log_file(bag)
    assert str(caught.value).startswith("bag: its metadata.yaml is unreadable: ")
