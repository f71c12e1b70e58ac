"""The intake process without ROS (its synthetic source): records and status cross the pipe,
and the process ends with the app in every way the app can end."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import threading

import pytest

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record_batch import RecordColumns
from console_tui.sources.intake_process.child import Sender
from console_tui.sources.intake_process.frames import BATCH, STATUS, read_frames, status_from, write_frame
from console_tui.sources.intake_process.parent import ProcessSource
from console_tui.sources.intake_process.synthetic import synthetic_record
from console_tui.sources.status import SourceStatus

from support.rosproc import pid_alive, wait_until


def collect(queue: IntakeQueue, enough: int, timeout: float = 20.0) -> list:
    records: list = []

    def done() -> bool:
        records.extend(queue.drain())
        return len(records) >= enough

    assert wait_until(done, timeout), f"{len(records)} of {enough} records arrived"
    return records


def test_records_and_status_cross_the_pipe_in_order_then_stop_ends_the_process():
    queue = IntakeQueue()
    source = ProcessSource(queue, "synthetic", args=["--rate", "20000", "--count", "5000"])
    source.start()
    try:
        records = collect(queue, 5000)
        assert wait_until(lambda: source.status.path == "synthetic" and source.status.running)
    finally:
        source.stop()
    assert [(r.stamp_ns, r.msg, r.node, r.file, r.line) for r in records] == [
        (r.stamp_ns, r.msg, r.node, r.file, r.line) for r in map(synthetic_record, range(5000))
    ]
    assert source.process is not None and source.process.returncode == 0
    assert not pid_alive(source.process.pid)
    assert source.status.running is False and source.status.problem == ""


def test_a_status_that_changed_before_records_were_taken_is_sent_before_them():
    """The app learns of a new topic before that topic's history (placed by its stamps then)."""

    class Switching:
        status = SourceStatus(topic="/rosout")

    read_end, write_end = os.pipe()
    queue = IntakeQueue()
    sender = Sender(write_end, queue)
    source = Switching()
    sender.flush(source)
    source.status = SourceStatus(topic="/rosout_agg")
    queue.put(RecordColumns.from_records([synthetic_record(0)]))
    sender.flush(source)
    os.close(write_end)
    frames = [
        (kind, status_from(payload).topic if kind == STATUS else "records") for kind, payload in read_frames(read_end)
    ]
    os.close(read_end)
    assert frames == [(STATUS, "/rosout"), (STATUS, "/rosout_agg"), (BATCH, "records")]


def test_the_batches_queued_between_two_flushes_cross_as_one_frame():
    """The source queues a batch a turn of its loop; the app pays for each batch it takes in,
    so what a flush finds goes as one, in order."""
    from console_tui.model.store.record_batch import BatchUnpacker
    from console_tui.sources.intake_process.child import FRAME_RECORDS

    class Steady:
        status = SourceStatus(topic="/rosout")

    read_end, write_end = os.pipe()
    queue = IntakeQueue()
    sender = Sender(write_end, queue)
    total = FRAME_RECORDS + 300
    for start in range(0, total, 100):
        queue.put(RecordColumns.from_records([synthetic_record(n) for n in range(start, min(start + 100, total))]))
    frames: list = []
    reader = threading.Thread(target=lambda: frames.extend(read_frames(read_end)))  # the pipe holds less
    reader.start()
    sender.flush(Steady())
    os.close(write_end)
    reader.join(30)
    os.close(read_end)
    unpacker = BatchUnpacker()
    batches = [unpacker.unpack(payload) for kind, payload in frames if kind == BATCH]
    assert [len(batch) for batch in batches] == [FRAME_RECORDS, 300]  # at most FRAME_RECORDS a frame
    assert [m for batch in batches for m in batch.msgs] == [synthetic_record(n).msg for n in range(total)]


def test_batches_reach_the_queue_as_columns():
    queue = IntakeQueue()
    source = ProcessSource(queue, "synthetic", args=["--rate", "5000", "--count", "100"])
    source.start()
    try:
        assert wait_until(lambda: len(queue) >= 100)
        batches = queue.drain_batches()
    finally:
        source.stop()
    assert batches and all(isinstance(batch, RecordColumns) for batch in batches)


def test_what_the_apps_full_queue_drops_counts_as_lost():
    queue = IntakeQueue(limit=10)
    source = ProcessSource(queue, "synthetic", args=["--rate", "5000", "--count", "500"])
    source.start()
    try:
        assert wait_until(lambda: queue.received >= 500)
        assert wait_until(lambda: source.status.lost_queue == queue.dropped > 0)
    finally:
        source.stop()
    assert source.status.lost == source.status.lost_queue == 500 - len(queue)
    assert "UI behind" in source.status.loss_text()


def test_a_process_that_dies_says_so_and_is_not_waited_for():
    queue = IntakeQueue()
    source = ProcessSource(queue, "synthetic", args=["--rate", "100"])
    source.start()
    try:
        assert wait_until(lambda: source.status.running)
        assert source.pid is not None
        os.kill(source.pid, signal.SIGKILL)
        assert wait_until(lambda: not source.status.running)
        assert "the intake process ended (exit status -9)" in source.status.problem
    finally:
        source.stop()


def test_a_source_started_twice_starts_one_process():
    """``run_app`` starts the live intake before the app is made; the app's ``start_sources``
    after its first frame must not start a second process reading the same topic."""
    queue = IntakeQueue()
    source = ProcessSource(queue, "synthetic", args=["--rate", "100"])
    assert not source.started
    source.start()
    try:
        assert wait_until(lambda: source.pid is not None)
        first, reader = source.pid, source._reader
        source.start()
        assert source.started and source._reader is reader and source.pid == first
    finally:
        source.stop()


def test_a_source_that_cannot_start_says_why():
    queue = IntakeQueue()
    source = ProcessSource(queue, "ros2", env={**os.environ, "RMW_IMPLEMENTATION": "rmw_no_such_thing"})
    source.start()
    try:
        assert wait_until(lambda: source.status.problem != "")
    finally:
        source.stop()
    assert "intake" in source.status.problem and not source.status.running


def test_a_source_that_raises_as_it_starts_sends_why_and_exits_2():
    """rclpy refuses a ROS_DOMAIN_ID that is not a number: the intake process says so in a
    status frame (the app shows it) and ends with 2, rather than dying without a word."""
    child = subprocess.run(
        [sys.executable, "-m", "console_tui.sources.intake_process.child", "ros2"],
        env={**os.environ, "ROS_DOMAIN_ID": "not a number"},
        stdin=subprocess.DEVNULL,
        capture_output=True,
        timeout=60,
    )
    assert child.returncode == 2, child.stderr.decode()[-2000:]
    read, write = os.pipe()
    os.write(write, child.stdout)
    os.close(write)
    frames = list(read_frames(read))
    os.close(read)
    assert [kind for kind, _ in frames] == [STATUS]
    status = status_from(frames[0][1])
    assert status.problem.startswith("the live intake could not start: ") and not status.running


def test_an_intake_process_whose_app_is_already_gone_ends_at_once():
    gone = subprocess.Popen([sys.executable, "-c", "pass"])
    gone.wait()
    child = subprocess.run(
        [sys.executable, "-m", "console_tui.sources.intake_process.child", "synthetic", "--parent", str(gone.pid)],
        stdin=subprocess.PIPE,
        capture_output=True,
        timeout=60,
    )
    assert (child.returncode, child.stdout) == (0, b""), "no frame, no record: the app is not there to read them"


@pytest.mark.parametrize("how", ["SIGKILL", "SIGTERM", "exit"])
def test_the_process_ends_when_the_app_ends_however_it_ends(how):
    script = textwrap.dedent(
        f"""
        import os, signal, sys, time
        from console_tui.model.store.intake_queue import IntakeQueue
        from console_tui.sources.intake_process.parent import ProcessSource
        source = ProcessSource(IntakeQueue(), "synthetic", args=["--rate", "1000"])
        source.start()
        while not source.status.running:  # the intake process is up and sending
            time.sleep(0.01)
        print(source.pid, flush=True)
        sys.stdin.readline()
        if {how!r} == "exit":
            os._exit(0)  # no stop(), no clean-up at all
        time.sleep(60)
        """
    )
    app = subprocess.Popen([sys.executable, "-c", script], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    child = int(app.stdout.readline())
    assert pid_alive(child)
    if how == "exit":
        app.stdin.write("\n")
        app.stdin.flush()
    else:
        app.send_signal(getattr(signal, how))
    app.wait(10)
    assert wait_until(lambda: not pid_alive(child)), "the intake process outlived the app"


def test_frames_round_trip_and_a_cut_frame_is_not_read():
    read, write = os.pipe()
    status = SourceStatus(topic="/rosout", publishers=3, lost=2, lost_qos=2, running=True)
    write_frame(write, BATCH, b"x" * 20_000)
    write_frame(write, STATUS, b'{"topic": "/rosout", "publishers": 3, "lost": 2, "lost_qos": 2, "running": true}')
    os.write(write, b"\x01\xff\x00\x00\x00cut")
    os.close(write)
    frames = list(read_frames(read))
    os.close(read)
    assert [kind for kind, _ in frames] == [BATCH, STATUS]
    assert frames[0][1] == b"x" * 20_000 and status_from(frames[1][1]) == status
