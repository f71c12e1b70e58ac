"""The hand-off queue between a source's thread and the UI: order, limits, split batches."""

from __future__ import annotations

import threading
import time

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns


def batch(first: int, count: int) -> list[LogRecord]:
    return [LogRecord(stamp_ns=i, level=20, node="n", msg=f"m{i}") for i in range(first, first + count)]


def stamps(records: list[LogRecord]) -> list[int]:
    return [r.stamp_ns for r in records]


def test_drain_with_a_limit_splits_a_batch_and_keeps_the_rest_in_order():
    queue = IntakeQueue()
    queue.put(RecordColumns.from_records(batch(0, 5)))
    queue.put(RecordColumns.from_records(batch(5, 5)))
    assert stamps(queue.drain(3)) == [0, 1, 2]
    assert len(queue) == 7, "the rest of the split batch still waits"
    assert stamps(queue.drain(4)) == [3, 4, 5, 6], "the rest first, then the next batch, split again"
    assert len(queue) == 3
    assert stamps(queue.drain()) == [7, 8, 9]
    assert len(queue) == 0 and queue.drain() == [] and queue.drain(5) == []
    assert queue.received == 10 and queue.dropped == 0


def test_drain_with_a_limit_of_whole_batches_and_more_than_is_waiting():
    queue = IntakeQueue()
    queue.put(RecordColumns.from_records(batch(0, 2)))
    queue.put(RecordColumns.from_records(batch(2, 2)))
    assert stamps(queue.drain(2)) == [0, 1] and len(queue) == 2
    assert stamps(queue.drain(100)) == [2, 3] and len(queue) == 0


def test_a_full_queue_counts_whole_batches_as_dropped_and_takes_them_again_when_drained():
    queue = IntakeQueue(limit=5)
    queue.put(RecordColumns.from_records(batch(0, 3)))
    queue.put(RecordColumns.from_records(batch(3, 3)))  # 6 would be over 5: dropped whole, counted
    queue.put(RecordColumns.from_records(batch(6, 2)))  # 5 fits exactly
    queue.put(RecordColumns.from_records([]))  # nothing to count
    assert len(queue) == 5 and queue.dropped == 3 and queue.received == 8
    assert stamps(queue.drain()) == [0, 1, 2, 6, 7]
    queue.put(RecordColumns.from_records(batch(8, 5)))
    assert stamps(queue.drain()) == [8, 9, 10, 11, 12] and queue.dropped == 3


def test_batches_from_several_threads_arrive_whole_and_none_is_lost():
    queue = IntakeQueue()

    def produce(base: int) -> None:
        for n in range(200):
            queue.put(RecordColumns.from_records(batch(base + n * 3, 3)))

    threads = [threading.Thread(target=produce, args=(k * 100_000,)) for k in range(4)]
    for thread in threads:
        thread.start()
    got: list[LogRecord] = []
    deadline = time.monotonic() + 10
    while (any(t.is_alive() for t in threads) or len(queue)) and time.monotonic() < deadline:
        got.extend(queue.drain(7))
    for thread in threads:
        thread.join()
    got.extend(queue.drain())
    assert len(got) == 2400 and queue.received == 2400
    for k in range(4):  # each producer's records in its own order
        own = [s for s in stamps(got) if k * 100_000 <= s < (k + 1) * 100_000]
        assert own == sorted(own) and len(own) == 600
