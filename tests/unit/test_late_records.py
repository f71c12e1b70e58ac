"""A late history placed by its stamp among the store's newest records (no ROS): the store,
the view (with and without rules), the storms, the timeline, the node counts and the marks
read as if the records had come in time order."""

from __future__ import annotations

from console_tui.model.overview.node_stats import NodeStats
from console_tui.model.overview.storms import StormRows
from console_tui.model.overview.timeline import Timeline
from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import RuleSet
from console_tui.model.store.late_records import LATE_NS, add_in_time_order
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.model.view.log_view import LogView
from console_tui.model.view.marks import Marks

from support.followers import assert_follow_as_made_again

INFO, WARN, ERROR = 20, 30, 40
S = 1_000_000_000
BASE = 1_700_000_000 * S


def history(node: str, count: int, start_s: float, step_s: float = 0.1, text: str = "tick {i}") -> RecordColumns:
    """``count`` messages of ``node``, ``step_s`` apart from ``start_s``: a node's history."""
    levels = (INFO, INFO, WARN, INFO, ERROR)
    return RecordColumns.from_records(
        [LogRecord(BASE + int((start_s + i * step_s) * S), levels[i % 5], node, text.format(i=i)) for i in range(count)]
    )


def stamps(store: LogStore) -> list[int]:
    return [store.stamp_of(seq) for seq in range(store.first_seq, store.end_seq)]


def fresh(records: list[LogRecord]) -> LogStore:
    """A store that got ``records`` in time order."""
    store = LogStore()
    for record in records:
        record.seq = -1
    store.extend_records(sorted(records, key=lambda r: r.stamp_ns))
    return store


def test_a_late_history_is_placed_by_its_stamp_and_a_timely_batch_is_appended():
    store = LogStore()
    assert add_in_time_order(store, history("/a", 50, 10.0)) is None  # empty store: appended
    placed = add_in_time_order(store, history("/b", 50, 8.0))  # 2 s older than /a's newest
    assert placed is not None
    assert stamps(store) == sorted(stamps(store))
    assert len(store) == 100 and store.counts[ERROR] == 20
    nodes = [store.get(seq).node for seq in range(store.first_seq, store.end_seq)]
    assert nodes[:20] == ["/b"] * 20  # /b's 8.0 .. 9.9 s, then the two interleave
    newest = store.stamp_of(store.end_seq - 1)
    # Delivery a little out of order (less than LATE_NS) is appended as it comes.
    slightly = history("/c", 1, (newest - BASE - LATE_NS // 2) / S)
    assert add_in_time_order(store, slightly) is None
    assert store.get(store.end_seq - 1).node == "/c"


def test_histories_in_one_batch_are_sorted_and_with_no_window_rows_stay_put():
    store = LogStore()
    both = RecordColumns.joined([history("/a", 20, 10.0), history("/b", 20, 9.0)])
    assert add_in_time_order(store, both) is None  # nothing moved: only the batch was sorted
    assert stamps(store) == sorted(stamps(store)) and len(store) == 40
    before = [store.get(seq) for seq in range(store.end_seq)]
    assert (
        add_in_time_order(store, RecordColumns.joined([history("/c", 5, 12.0), history("/c", 5, 5.0)]), window=0)
        is None
    )
    assert [store.get(seq) for seq in range(40)] == before  # the rows there stay as they were
    assert stamps(store)[40:] == sorted(stamps(store)[40:])


def test_placing_is_bounded_by_its_window_and_keeps_the_records():
    store = LogStore()
    store.extend(history("/a", 3 * CHUNK_SIZE, 0.0, step_s=0.01))
    before = len(store)
    add_in_time_order(store, history("/b", 100, 1.0, step_s=0.001), window=500)
    assert len(store) == before + 100
    tail = stamps(store)[-600:]
    assert tail == sorted(tail)
    assert store.first_seq == 0 and sum(store.counts.values()) == len(store)
    assert sorted(r.msg for r in store if r.node == "/b") == sorted(f"tick {i}" for i in range(100))


def test_views_storms_timeline_and_counts_follow_a_late_history():
    store = LogStore()
    view = LogView(store)
    storms, timeline, stats = StormRows(store, view), Timeline(store, view), NodeStats(store)
    marks = Marks()
    store.extend(history("/a", 300, 10.0, text="same {i}").reordered([i // 3 * 3 for i in range(300)]))  # storms of 3
    view.set_rules(RuleSet().with_query(parse_query("level>=warn", utc=True)))
    for follower in (storms, timeline):
        follower.sync()
    stats.update()
    marked = store.end_seq - 1
    marked_record = store.get(marked)
    marks.toggle(marked)
    placed = add_in_time_order(store, history("/b", 200, 5.0))
    assert placed is not None
    marks.move(placed.moved)
    view.update()
    for follower in (storms, timeline):
        follower.sync()
    stats.update()
    (mark,) = list(marks)
    assert store.get(mark).msg == marked_record.msg and store.get(mark).stamp_ns == marked_record.stamp_ns

    assert_follow_as_made_again(view, storms, timeline, stats, fresh(list(store)))


def test_histories_are_due_for_a_while_after_a_source_starts_gains_a_publisher_or_changes_topic():
    from console_tui.model.store.late_records import HistoryWindow

    now = [0.0]
    window = HistoryWindow(lambda: now[0], seconds=3.0)
    assert not window.due()
    window.note("a", 1, "/rosout")  # a source seen for the first time
    assert window.due()
    now[0] = 5.0
    window.note("a", 1, "/rosout")
    assert not window.due()
    window.note("a", 0, "/rosout")  # a publisher left: no history comes with that
    assert not window.due()
    window.note("a", 1, "/rosout")  # one joined
    assert window.due()
    now[0] = 10.0
    window.note("a", 1, "/rosout_agg")  # the switch to /rosout_agg
    assert window.due()
    now[0] = 13.5
    window.note("a", 1, "/rosout_agg")
    assert not window.due()
