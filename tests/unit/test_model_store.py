"""The bounded store: seqs, eviction at the bound, counts, spans, clear."""

import pytest

from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord


def make(i: int, level: int = 20) -> LogRecord:
    return LogRecord(
        stamp_ns=1_700_000_000_000_000_000 + i,
        level=level,
        node=f"node{i % 3}",
        msg=f"message {i}",
        file="f.cpp",
        function="fn",
        line=i % 1000,
        source="/rosout",
    )


def test_extend_assigns_seqs_and_get_returns_every_field():
    store = LogStore(max_messages=10)
    added = store.extend_records(make(i) for i in range(3))
    assert list(added) == [0, 1, 2]
    record = store.get(1)
    assert record.msg == "message 1"
    assert (
        record.stamp_ns,
        record.level,
        record.node,
        record.file,
        record.function,
        record.line,
        record.source,
        record.seq,
    ) == (1_700_000_000_000_000_001, 20, "node1", "f.cpp", "fn", 1, "/rosout", 1)


def test_bound_drops_oldest_and_keeps_numbering():
    store = LogStore(max_messages=5)
    store.extend_records(make(i) for i in range(12))
    assert len(store) == 5
    assert store.first_seq == 7 and store.end_seq == 12
    assert [r.msg for r in store] == [f"message {i}" for i in range(7, 12)]
    assert store.evicted == 7
    with pytest.raises(KeyError):
        store.get(6)


def test_eviction_across_chunks_releases_chunks():
    store = LogStore(max_messages=CHUNK_SIZE + 10)
    store.extend_records(make(i) for i in range(CHUNK_SIZE * 5 + 3))
    assert len(store) == CHUNK_SIZE + 10
    assert len(store._chunks) <= 3
    assert store.get(store.first_seq).msg == f"message {store.first_seq}"
    assert store.get(store.end_seq - 1).msg == f"message {store.end_seq - 1}"


def test_counts_follow_eviction_and_clear():
    store = LogStore(max_messages=4)
    store.extend_records([make(0, 10), make(1, 30), make(2, 40), make(3, 40), make(4, 50)])
    assert store.counts == {10: 0, 20: 0, 30: 1, 40: 2, 50: 1}
    store.clear()
    assert len(store) == 0 and store.counts[40] == 0
    added = store.extend_records([make(9)])
    assert list(added) == [5]
    assert store.get(5).msg == "message 9"


def test_clear_mid_chunk_then_fill_past_chunk():
    store = LogStore(max_messages=CHUNK_SIZE * 2)
    store.extend_records(make(i) for i in range(100))
    store.clear()
    store.extend_records(make(i) for i in range(CHUNK_SIZE + 50))
    assert store.first_seq == 100
    assert store.get(100 + CHUNK_SIZE + 49).msg == f"message {CHUNK_SIZE + 49}"


def test_spans_cover_range_both_directions():
    store = LogStore(max_messages=CHUNK_SIZE * 3)
    store.extend_records(make(i) for i in range(CHUNK_SIZE * 2 + 7))
    spans = list(store.spans(5, CHUNK_SIZE * 2 + 3))
    assert sum(s.hi - s.lo for s in spans) == CHUNK_SIZE * 2 - 2
    assert spans[0].seq == 5
    backwards = list(store.spans(5, CHUNK_SIZE * 2 + 3, newest_first=True))
    assert [s.seq for s in backwards] == [s.seq for s in reversed(spans)]


def test_out_of_range_values_are_clamped_not_fatal():
    store = LogStore()
    store.append(LogRecord(stamp_ns=1 << 80, level=999, node="n", msg="m", line=-5))
    record = store.get(0)
    assert record.level == 255 and record.line == 0 and record.stamp_ns == (1 << 63) - 1


def test_bad_values_in_a_batch_are_clamped_and_the_rest_kept_exactly():
    store = LogStore()
    good = [make(i, level=30) for i in range(CHUNK_SIZE - 2)]
    bad = [
        LogRecord(stamp_ns=-(1 << 70), level=-3, node="new node", msg="low", line=1 << 40),
        LogRecord(stamp_ns=5.0, level=20.0, node="node1", msg="floats", line=7.9),  # type: ignore[arg-type]
    ]
    added = store.extend_records([*good[:10], *bad, *good[10:], make(99_999, level=40)])  # the last one starts a chunk
    assert len(added) == CHUNK_SIZE + 1
    assert [store.get(seq).msg for seq in (9, 10, 11, 12)] == ["message 9", "low", "floats", "message 10"]
    low, floats = store.get(10), store.get(11)
    assert (low.stamp_ns, low.level, low.line, low.node) == (-(1 << 63) + 1, 0, 0xFFFFFFFF, "new node")
    assert (floats.stamp_ns, floats.level, floats.line) == (5, 20, 7)
    assert store.get(CHUNK_SIZE).msg == "message 99999" and store.get(CHUNK_SIZE).seq == CHUNK_SIZE
    assert sum(store.counts.values()) == len(store)
    assert store.counts[30] == CHUNK_SIZE - 2 and store.counts[40] == 1


def test_max_messages_must_be_positive():
    with pytest.raises(ValueError):
        LogStore(max_messages=0)


def test_ros1_topics_are_kept_and_cost_nothing_for_records_without():
    store = LogStore()
    store.extend_records(make(i) for i in range(CHUNK_SIZE + 10))  # ROS 2 records: no topics column made
    assert all(chunk.topics is None for chunk in store._chunks)
    with_topics = make(99)
    with_topics.topics = "/rosout,/chatter"
    store.extend_records([make(100), with_topics, make(101)])
    last = store._chunks[-1]
    assert last.topics is not None and len(last.topics) == len(last)
    assert [store.get(seq).topics for seq in range(store.end_seq - 4, store.end_seq)] == [
        "",
        "",
        "/rosout,/chatter",
        "",
    ]


def test_evict_listeners_see_the_records_that_go():
    store = LogStore(max_messages=5000)
    seen = []

    def going(first, new_first):
        assert store.first_seq == first
        seen.append((first, new_first, [store.get(seq).msg for seq in (first, new_first - 1)]))

    store.evict_listeners.append(going)
    store.extend_records(LogRecord(stamp_ns=i, level=20, node="n", msg=f"m{i}") for i in range(6000))
    assert seen == [(0, 1000, ["m0", "m999"])]
    assert store.stamp_of(1000) == 1000 and store.nodes[store.node_id_of(1000)] == "n"
