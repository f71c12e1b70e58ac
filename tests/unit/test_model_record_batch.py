"""Record batches in columns, packed into bytes and back, and into the store."""

import pytest

from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.packed_texts import PackedTexts
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import BatchError, BatchPacker, BatchUnpacker, ColumnsBuilder, RecordColumns


def make(i: int, msg: str | None = None) -> LogRecord:
    return LogRecord(
        1_700_000_000_000_000_000 + i,
        [10, 20, 30, 40, 50][i % 5],
        f"node{i % 3}",
        f"message {i}" if msg is None else msg,
        "f.cpp",
        f"fn{i % 2}",
        i % 70_000,
        "/rosout",
    )


HOSTILE = ["", "with\0nul", "ünïcødé ☃", "\ud800 lone surrogate", "multi\nline", "x" * 5000]


def fields(records):
    return [(r.stamp_ns, r.level, r.node, r.msg, r.file, r.function, r.line, r.source) for r in records]


@pytest.mark.parametrize("texts", [["plain"] * 3, HOSTILE], ids=["plain", "hostile"])
def test_pack_then_unpack_gives_the_same_records(texts):
    packer, unpacker = BatchPacker(), BatchUnpacker()
    first = [make(i, text) for i, text in enumerate(texts)]
    second = [make(i + 100) for i in range(5)]
    for batch in (first, second, []):
        assert fields(unpacker.unpack(packer.pack(RecordColumns.from_records(batch))).records()) == fields(batch)


def test_strings_travel_once_and_a_new_table_starts_when_full():
    packer, unpacker = BatchPacker(table_limit=40), BatchUnpacker()
    sizes = []
    for round_ in range(6):
        batch = [make(i) for i in range(round_ * 5, round_ * 5 + 5)]
        data = packer.pack(RecordColumns.from_records(batch))
        sizes.append(len(data))
        assert fields(unpacker.unpack(data).records()) == fields(batch)
    assert sizes[1] < sizes[0]  # the second batch names no new node, file or function


def test_damaged_batches_are_refused():
    data = BatchPacker().pack(RecordColumns.from_records([make(i) for i in range(4)]))
    for damaged in (data[:-1], data[:10], data + b"x", b""):
        with pytest.raises(BatchError):
            BatchUnpacker().unpack(damaged)


def test_columns_slice_and_store_take_them_whole():
    columns = RecordColumns.from_records([make(i) for i in range(CHUNK_SIZE + 10)])
    assert fields(columns.slice(3, 5).records()) == fields([make(3), make(4)])
    store = LogStore()
    added = store.extend(columns)
    assert list(added) == list(range(CHUNK_SIZE + 10))
    assert fields([store.get(0), store.get(CHUNK_SIZE + 9)]) == fields([make(0), make(CHUNK_SIZE + 9)])


def test_columns_joined_and_kept_in_order():
    parts = [RecordColumns.from_records([make(i) for i in range(lo, hi)]) for lo, hi in ((0, 3), (3, 3), (3, 7))]
    joined = RecordColumns.joined(parts)
    assert fields(joined.records()) == fields([make(i) for i in range(7)])
    assert joined.topics is None and len(RecordColumns.joined([])) == 0
    kept = joined.kept([i % 3 == 0 for i in range(7)])
    assert fields(kept.records()) == fields([make(0), make(3), make(6)])
    with_topics = make(9)
    with_topics.topics = "/chatter"
    mixed = RecordColumns.joined([parts[0], RecordColumns.from_records([with_topics])])
    assert mixed.topics == ["", "", "", "/chatter"]
    assert mixed.kept([False, False, True, True]).topics == ["", "/chatter"]


def test_store_widens_columns_for_big_ids_and_lines():
    store = LogStore()
    store.extend_records([make(i) for i in range(10)])
    store.extend_records(
        [LogRecord(5, 20, f"n{i}", "m", "f", "g", 100_000 + i, "s") for i in range(70_000)]
    )  # more than 65,536 node names
    assert store.get(3).line == 3
    last = store.get(store.end_seq - 1)
    assert (last.node, last.line) == ("n69999", 169_999)
    assert store.get(9).node == "node0"


def test_full_chunks_keep_their_messages_packed_and_read_the_same():
    store = LogStore()
    texts = [f"message {i}" for i in range(CHUNK_SIZE * 2 + 1)]
    texts[5] = "ünïcødé"
    store.extend_records([make(i, text) for i, text in enumerate(texts)])
    chunk = next(store.spans(0, 1)).chunk
    assert isinstance(chunk.msgs, PackedTexts)
    assert chunk.msgs[3:7] == texts[3:7] and chunk.msgs[5] == "ünïcødé" and chunk.msgs[-1] == texts[CHUNK_SIZE - 1]
    assert [store.get(seq).msg for seq in range(store.end_seq)] == texts


def test_ros1_topics_travel_and_are_stored_only_where_there_are_some():
    plain = [make(i) for i in range(3)]
    with_topics = [make(i) for i in range(3, 6)]
    for record in with_topics:
        record.topics = "/chatter,/rosout"
    packer, unpacker = BatchPacker(), BatchUnpacker()
    store = LogStore()
    store.extend(unpacker.unpack(packer.pack(RecordColumns.from_records(plain))))
    assert next(store.spans(0, 1)).chunk.topics is None
    store.extend(unpacker.unpack(packer.pack(RecordColumns.from_records(with_topics))))
    store.extend_records(plain)
    assert [store.get(seq).topics for seq in range(9)] == [""] * 3 + ["/chatter,/rosout"] * 3 + [""] * 3


def test_a_columns_builder_gives_each_record_its_source_and_forgets_what_it_is_told():
    batch = ColumnsBuilder()
    for i, (tail, source) in enumerate(
        [(("f", "g", 1, ""), "/a"), (("f", "g", 2, "/t"), "/a"), (("h", "k", 3, ""), "/b")]
    ):
        batch.stamps.append(i)
        batch.levels.append(20)
        batch.nodes.append(f"n{i}")
        batch.msgs.append(f"m{i}")
        batch.tails.append(tail)
        batch.sourced(source)
    assert len(batch) == 3 and batch.key(1) == (1, "n1", "m1")
    records = batch.columns().records()
    assert [(r.source, r.topics, r.line) for r in records] == [("/a", "", 1), ("/a", "/t", 2), ("/b", "", 3)]
    batch.drop(1)
    assert [(r.msg, r.source) for r in batch.columns().records()] == [("m0", "/a"), ("m2", "/b")]
    assert batch.columns().topics is None, "no record left with topics"
    batch.cut(1)
    assert batch.columns().records() == [LogRecord(0, 20, "n0", "m0", "f", "g", 1, "/a")]
    batch.cut(0)
    assert len(batch.columns()) == 0
