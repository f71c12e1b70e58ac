"""console-tui rosout's rosout.log: exact round trip, detection, rotation; the Log CDR encoder."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from console_tui.model.formats import Ros2RosoutLogFormat, RosoutLogFormat, rotating_file, text_formats
from console_tui.model.formats.ros2_log_msg import LogDecoder, LogEncoder
from console_tui.model.formats.rosout_log import ROS2_HEADER, rosout_log_text
from console_tui.model.formats.rotating_file import RotatingFile
from console_tui.model.store.record import LogRecord
from console_tui.sources.files import open_log_file

from support.formats import fields, hostile_records, read_cleanly, read_text


def written(records: list[LogRecord]) -> bytes:
    return (ROS2_HEADER + "".join(rosout_log_text(r) for r in records)).encode()


def test_lines_look_like_ros1_rosout_log():
    record = LogRecord(1_763_805_921_123_456_789, 40, "nav.planner", "Planner failed:\nno path", "p.cpp", "plan", 120)
    assert (
        rosout_log_text(record)
        == "1763805921.123456789 ERROR nav.planner [p.cpp:120(plan)] Planner failed:\n\tno path\n"
    )
    odd = LogRecord(5, 25, "a b%", "", "C:\\src (x)\\f.cpp", "operator()[with T]", 0)
    assert rosout_log_text(odd) == "0.000000005 25 a%20b%25 [C:\\src %28x)\\f.cpp:0(operator()[with T%5D)] \n"


def test_hostile_records_read_back_exactly():
    records = hostile_records("rosout.log")
    back = read_cleanly(written(records), Ros2RosoutLogFormat(), "rosout.log")
    assert [fields(r) for r in back] == [fields(r) for r in records]


text = st.text(st.characters(blacklist_categories=("Cs",), blacklist_characters="\0"), max_size=40)


@settings(max_examples=300, deadline=None)
@given(
    st.lists(
        st.builds(
            LogRecord,
            stamp_ns=st.integers(-(2**31) * 10**9, 2**31 * 10**9),
            level=st.integers(0, 255),
            node=text,
            msg=text,
            file=text,
            function=text,
            line=st.integers(0, 2**32 - 1),
            source=st.just("r.log"),
        ),
        max_size=5,
    )
)
def test_any_record_reads_back_exactly(records):
    back = read_cleanly(written(records), Ros2RosoutLogFormat(), "r.log")
    assert [fields(r) for r in back] == [fields(r) for r in records]


def test_detected_by_its_header_and_ros1_files_still_read_as_ros1(tmp_path):
    path = tmp_path / "rosout.log"
    path.write_bytes(written(hostile_records()))
    assert open_log_file(path).kind == "rosout2"
    ros1 = tmp_path / "ros1.log"
    ros1.write_bytes(b"\n\n1.000000000  Node Startup\n1.000000001 INFO /talker [t.py:1(f)] [topics: /rosout] hi\n")
    assert open_log_file(ros1).kind == "rosout"
    assert any(isinstance(f, Ros2RosoutLogFormat) for f in text_formats())
    assert not RosoutLogFormat().looks_like(ROS2_HEADER.strip())


def test_header_lines_in_the_middle_are_skipped():
    one, two = hostile_records()[:2]
    data = written([one]) + written([two])  # cat rosout.log.1 rosout.log
    back, problems = read_text(data, Ros2RosoutLogFormat(), "")
    assert list(problems) == [] and [r.msg for r in back] == [one.msg, two.msg]


def lines(count: int, start: int = 0) -> list[str]:
    return [rosout_log_text(LogRecord(n, 20, "n", f"message {n:04d}")) for n in range(start, start + count)]


def test_rotation_keeps_the_configured_count(tmp_path):
    path = tmp_path / "rosout.log"
    log = RotatingFile(path, max_bytes=1000, keep=3, header=ROS2_HEADER)
    for number in range(200):
        log.write(lines(1, number))
    log.close()
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["rosout.log", "rosout.log.1", "rosout.log.2", "rosout.log.3"]
    kept = []
    for file in log.files():  # oldest first
        data = file.read_bytes()
        assert data.startswith(ROS2_HEADER.encode()) and len(data) <= 1000
        back = read_cleanly(data, Ros2RosoutLogFormat())
        kept += [r.stamp_ns for r in back]
    assert kept == list(range(kept[0], 200))  # the newest, none missing in between
    assert log.rotations > 3


def test_a_batch_is_split_at_a_line_when_rotating_and_keep_zero_removes(tmp_path):
    path = tmp_path / "rosout.log"
    log = RotatingFile(path, max_bytes=2000, keep=0, header=ROS2_HEADER)
    log.write(lines(100))
    log.close()
    assert [p.name for p in tmp_path.iterdir()] == ["rosout.log"]
    back, problems = read_text(path.read_bytes(), Ros2RosoutLogFormat())
    assert list(problems) == [] and back[-1].stamp_ns == 99


def test_appends_to_its_own_file_and_moves_another_aside(tmp_path):
    path = tmp_path / "rosout.log"
    log = RotatingFile(path, max_bytes=10_000, keep=2, header=ROS2_HEADER)
    log.write(lines(2))
    log.close()
    log = RotatingFile(path, max_bytes=10_000, keep=2, header=ROS2_HEADER)
    log.write(lines(1, 2))
    log.close()
    back, _ = read_text(path.read_bytes(), Ros2RosoutLogFormat())
    assert [r.stamp_ns for r in back] == [0, 1, 2]
    other = tmp_path / "other" / "rosout.log"
    other.parent.mkdir()
    other.write_bytes(b"1.000000000 INFO /x [f:1(g)] a ROS 1 file\n")
    log = RotatingFile(other, max_bytes=10_000, keep=2, header=ROS2_HEADER)
    log.close()
    assert other.read_bytes() == ROS2_HEADER.encode()
    assert (other.parent / "rosout.log.1").read_bytes().endswith(b"a ROS 1 file\n")


def test_write_failures_are_counted_not_raised(tmp_path):
    path = tmp_path / "gone" / "rosout.log"
    log = RotatingFile(path, max_bytes=10_000, keep=1, header=ROS2_HEADER)
    log.close()
    os.remove(path)
    path.parent.rmdir()
    path.parent.write_text("a file where the directory was")
    log._open(existing=True)
    log.write(lines(3))
    assert log.lost == 3 and "gone" in log.error


def test_encoder_round_trips_through_the_decoder():
    encoder, decoder = LogEncoder(), LogDecoder()
    records = hostile_records("/rosout")
    assert decoder.decode_many([encoder.encode(r) for r in records], "/rosout") == records


@settings(max_examples=200, deadline=None)
@given(st.lists(text, min_size=4, max_size=4), st.integers(0, 255), st.integers(0, 2**32 - 1))
def test_encoder_any_strings(texts, level, line):
    name, msg, file, function = texts
    record = LogRecord(1_700_000_000_000_000_001, level, name, msg, file, function, line, "/rosout")
    data = LogEncoder().encode(record)
    assert len(data) % 4 == 0
    assert LogDecoder().decode(data, "/rosout") == record


def test_sizes_that_cannot_work_are_refused(tmp_path):
    for max_bytes, keep in ((0, 1), (1000, -1)):
        with pytest.raises(ValueError, match="max_bytes must be at least 1"):
            RotatingFile(tmp_path / "rosout.log", max_bytes=max_bytes, keep=keep)


def test_a_file_that_cannot_be_opened_is_tried_again_after_a_while(tmp_path, monkeypatch):
    blocker = tmp_path / "logs"
    blocker.write_text("a file where the directory should be")
    path = blocker / "rosout.log"
    log = RotatingFile(path, max_bytes=10_000, keep=1, header=ROS2_HEADER)
    assert str(path) in log.error
    log.write(lines(2))  # before the retry time: counted, not tried
    assert log.lost == 2
    monkeypatch.setattr(rotating_file, "RETRY_S", 0.0)
    log._failed(OSError(5, "Input/output error"))
    log.write(lines(3))  # tried again, fails again
    assert log.lost == 5 and "File exists" in log.error
    blocker.unlink()
    log.write(lines(1, 7))  # the directory can be made now
    log.close()
    assert log.error == "" and log.lost == 5
    back, problems = read_text(path.read_bytes(), Ros2RosoutLogFormat())
    assert list(problems) == [] and [r.stamp_ns for r in back] == [7]


_FULL_DISK = """
import json, resource, signal, sys
from console_tui.model.formats import rotating_file
from console_tui.model.formats.rotating_file import RotatingFile

signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails (EFBIG), as on a full disk
rotating_file.RETRY_S = 0.0
_, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
log = RotatingFile(sys.argv[1], max_bytes=10**9, keep=1, header="HEADER\\n")
resource.setrlimit(resource.RLIMIT_FSIZE, (5000, hard))
for n in range(100):
    log.write([f"line {n:04d} " + "x" * 80 + "\\n"])
    if n % 7 == 0:
        log.flush()
error = log.error
resource.setrlimit(resource.RLIMIT_FSIZE, (hard, hard))  # the space freed
for n in range(100, 110):
    log.write([f"line {n:04d} " + "x" * 80 + "\\n"])
log.close()
print(json.dumps({"written": log.written, "lost": log.lost, "error": error}))
"""


def test_a_full_disk_never_glues_a_record_to_a_cut_one_and_counts_each_line_once(tmp_path):
    path = tmp_path / "rosout.log"
    done = subprocess.run([sys.executable, "-c", _FULL_DISK, str(path)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    counts = json.loads(done.stdout)
    assert "File too large" in counts["error"]
    text = path.read_text()
    whole = re.compile(r"line \d{4} x{80}\Z")
    rows = text.split("\n")
    assert rows[0] == "HEADER" and rows[-1] == ""
    complete = [row for row in rows[1:-1] if whole.match(row)]
    cut = [row for row in rows[1:-1] if not whole.match(row)]
    assert len(cut) == 1 and len(cut[0]) < 90, "the cut line stands alone"
    assert [row[5:9] for row in complete][-10:] == [f"{n:04d}" for n in range(100, 110)]  # after: whole lines
    assert counts["written"] == len(complete) and counts["written"] + counts["lost"] == 110


def test_a_fifo_in_place_of_the_file_is_refused_not_waited_on(tmp_path):
    path = tmp_path / "rosout.log"
    os.mkfifo(path)
    script = (
        "import sys; from console_tui.model.formats.rotating_file import RotatingFile; "
        "log = RotatingFile(sys.argv[1], max_bytes=10000, keep=1); print(log.error)"
    )
    done = subprocess.run([sys.executable, "-c", script, str(path)], capture_output=True, text=True, timeout=60)
    assert "not a regular file" in done.stdout, done.stderr


def test_a_rotation_that_cannot_move_the_files_counts_the_lines(tmp_path):
    path = tmp_path / "rosout.log"
    (tmp_path / "rosout.log.1").mkdir()  # in the way of the oldest kept file
    (tmp_path / "rosout.log.1" / "something").write_text("kept")
    log = RotatingFile(path, max_bytes=600, keep=1, header=ROS2_HEADER)
    for number in range(20):
        log.write(lines(1, number))
    log.close()
    assert log.lost > 0 and "Is a directory" in log.error and log.rotations == 0
    back, problems = read_text(path.read_bytes(), Ros2RosoutLogFormat())
    assert list(problems) == [] and len(back) + log.lost == 20, "every line written or counted"
