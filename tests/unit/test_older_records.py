"""A log warehouse's older pages put before the records kept (``add_older``, with
``LogStore.put_before`` keeping the kept chunks whole), and one source's records taken out
(``drop_source``): the store, its counts, the view, storms, timeline and node counts end as a
store that got the same records in time order."""

from __future__ import annotations

import pytest

from console_tui.model.overview.node_stats import NodeStats
from console_tui.model.overview.storms import StormRows
from console_tui.model.overview.timeline import Timeline
from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import RuleSet
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.older_records import add_older, drop_source
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.model.view.log_view import LogView

from support.followers import assert_follow_as_made_again

S = 1_000_000_000
BASE = 1_765_000_000 * S


def page(first: int, count: int, source: str = "w") -> RecordColumns:
    """Records ``first .. first + count`` of a warehouse (each 10 ms after the one before)."""
    return RecordColumns.from_records(
        [
            LogRecord(
                BASE + (first + i) * 10_000_000,
                [10, 20, 20, 30, 40, 50][(first + i) % 6],
                f"/node{(first + i) % 7}",
                f"row {first + i}" if (first + i) % 5 else "the same text",
                f"f{(first + i) % 3}.cpp",
                "run",
                first + i,
                source=source,
                robot=f"r{(first + i) % 4}",
            )
            for i in range(count)
        ]
    )


def contents(store: LogStore) -> list[tuple]:
    return [(r.stamp_ns, r.level, r.node, r.msg, r.file, r.line, r.robot, r.source) for r in store]


def fresh(store: LogStore) -> LogStore:
    """A store that got ``store``'s records in one batch."""
    again = LogStore(store.max_messages)
    again.extend(store.columns(store.first_seq, store.end_seq))
    return again


@pytest.mark.parametrize(
    ("kept", "pages"),
    [
        (100, [50]),  # one chunk kept: written again whole
        (CHUNK_SIZE * 3 + 5, [7]),  # chunks kept whole, a small page
        (CHUNK_SIZE * 2, [CHUNK_SIZE * 2 - 1, 1, 3 * CHUNK_SIZE + 17, CHUNK_SIZE]),  # pages of every size, in turn
        (CHUNK_SIZE * 5 + 1, [CHUNK_SIZE * 4]),
    ],
)
def test_older_pages_go_before_the_kept_records_as_if_read_in_order(kept, pages):
    total = kept + sum(pages)
    store = LogStore()
    store.extend(page(total - kept, kept))
    marked = [store.first_seq, store.first_seq + kept // 2, store.end_seq - 1]
    marked_rows = [store.get(seq) for seq in marked]
    end = total - kept
    for size in pages:
        placed = add_older(store, page(end - size, size), marked)
        end -= size
        assert placed is not None
        marked = [placed.moved.get(seq, seq) for seq in marked]
        assert [store.get(seq).msg for seq in marked] == [r.msg for r in marked_rows]  # each mark on its record
        assert len(store) == kept + (total - kept - end)
    assert contents(store) == contents(fresh(store))
    assert [r.line for r in store] == list(range(total))
    assert store.counts == fresh(store).counts
    assert sum(store.counts.values()) == len(store) == total
    # and it goes on as a store does: appended to, evicted from, read by span
    store.extend(page(total, 10))
    assert store.get(store.end_seq - 1).line == total + 9
    spans = list(store.spans(store.first_seq, store.end_seq))
    assert sum(span.hi - span.lo for span in spans) == len(store)


def test_put_before_keeps_the_kept_chunks_and_is_bounded_by_max_messages():
    store = LogStore()
    store.extend(page(10 * CHUNK_SIZE, 4 * CHUNK_SIZE))
    second = next(store.spans(store.first_seq + CHUNK_SIZE, store.first_seq + CHUNK_SIZE + 1)).chunk
    add_older(store, page(9 * CHUNK_SIZE + 100, CHUNK_SIZE - 100))
    assert any(span.chunk is second for span in store.spans(store.first_seq, store.end_seq))  # not copied
    small = LogStore(max_messages=5 * CHUNK_SIZE)
    small.extend(page(10 * CHUNK_SIZE, 4 * CHUNK_SIZE))
    add_older(small, page(8 * CHUNK_SIZE, 2 * CHUNK_SIZE))
    assert len(small) == 5 * CHUNK_SIZE and small.get(small.end_seq - 1).line == 14 * CHUNK_SIZE - 1
    assert contents(small) == contents(fresh(small)) and small.counts == fresh(small).counts


def test_the_view_overview_and_node_counts_follow_older_pages_and_a_source_taken_out():
    store = LogStore()
    view = LogView(store)
    storms, timeline, stats = StormRows(store, view), Timeline(store, view), NodeStats(store)
    view.set_rules(RuleSet().with_query(parse_query("level>=info -robot:r2", utc=True)))
    store.extend(page(6 * CHUNK_SIZE, 2 * CHUNK_SIZE + 9))
    store.extend(page(0, 300, source="other"))
    for pages in ([CHUNK_SIZE + 3, 2 * CHUNK_SIZE], [5]):
        end = 6 * CHUNK_SIZE
        for size in pages:
            add_older(store, page(end - size, size))
            end -= size
        view.update()
        while not view.refilter_step(1.0):
            pass
        for follower in (storms, timeline):
            follower.sync()
        stats.update()
        assert_follow_as_made_again(view, storms, timeline, stats, fresh(store))
        dropped = drop_source(store, "other")
        assert dropped.dropped in (300, 0)
