"""The timeline's counts (``Timeline``) and the summary's (``NodeStats``, ``find_level``),
against brute force: as records arrive, under rules (hidden records not counted), with
eviction, over long and odd histories."""

import random

from console_tui.model.overview.node_stats import NodeStats
from console_tui.model.overview.shown_follower import sync_together
from console_tui.model.overview.storms import StormRows
from console_tui.model.overview.timeline import MAX_BUCKETS, Timeline
from console_tui.model.rules import NodeRule, RuleSet, SeverityRule, exclude
from console_tui.model.store.find_level import find_level, find_node, severity_range
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView

S = 1_000_000_000
SLOT = {10: 0, 20: 1, 30: 2, 40: 3, 50: 4}


def rec(stamp, level=20, node="a", msg="m"):
    return LogRecord(stamp_ns=stamp, level=level, node=node, msg=msg)


def shown(view):
    return [view.seq_at(r) for r in range(len(view))]


def brute_columns(store, view, columns):
    counts = [[0] * 5 for _ in range(len(columns))]
    firsts = [None] * len(columns)
    for seq in shown(view):
        record = store.get(seq)
        column = (record.stamp_ns - columns.start_ns) // columns.step_ns
        assert 0 <= column < len(columns), (record.stamp_ns, columns.start_ns, columns.step_ns)
        counts[column][SLOT[record.level]] += 1
        if firsts[column] is None:
            firsts[column] = seq
    return [tuple(c) for c in counts], firsts


def test_an_error_burst_in_the_middle_is_its_own_column():
    store = LogStore()
    store.extend_records(rec(i * S // 10) for i in range(1000))  # 100 s of INFO, ten a second
    store.extend_records(rec(50 * S + i, level=40) for i in range(30))  # 30 errors at 50 s
    view = LogView(store)
    timeline = Timeline(store, view)
    assert timeline.sync()
    columns = timeline.columns(100)
    assert len(columns) <= 100
    marked = [c for c, counts in enumerate(columns.counts) if counts[3]]
    assert len(marked) == 1 and 45 <= marked[0] <= 55
    assert columns.counts[marked[0]][3] == 30
    assert columns.first_seqs[marked[0]] is not None
    assert sum(columns.totals()) == 1030


def test_hidden_records_are_not_counted():
    store = LogStore()
    store.extend_records(rec(i * S, level=10 * (1 + i % 5), node=f"n{i % 3}") for i in range(300))
    view = LogView(store)
    timeline = Timeline(store, view)
    timeline.sync()
    view.set_rules(RuleSet((exclude(SeverityRule.of("debug", "info")),)))
    # While the view filters and the timeline counts again, it shows the counts from before.
    assert sum(timeline.columns(50).totals()) == 300
    while not view.refilter_step(0.01):
        pass
    while not timeline.sync(0.001):
        pass
    assert not timeline.recounting
    columns = timeline.columns(50)
    assert sum(columns.totals()) == len(view) == 180
    assert (brute_columns(store, view, columns)) == (list(columns.counts), list(columns.first_seqs))


def test_live_tail_and_eviction_against_brute_force():
    rng = random.Random(3)
    for _trial in range(30):
        store = LogStore(max_messages=rng.choice([100, 1000, 100_000]))
        view = LogView(store)
        timeline = Timeline(store, view)
        stamp = rng.randint(0, 10**18)
        for _ in range(rng.randint(2, 10)):
            batch = []
            for _ in range(rng.randint(1, 300)):
                stamp += rng.choice([1, 1000, 10**6, 10**8, S, 60 * S, 3600 * S]) * rng.random()
                stamp = int(stamp)
                batch.append(
                    rec(stamp + rng.randint(-S, S), level=rng.choice([10, 20, 30, 40, 50]), node=rng.choice("abc"))
                )
            store.extend_records(batch)
            view.update()
            if rng.random() < 0.2:
                view.set_rules(RuleSet((exclude(NodeRule(("b",))),)), first_screen=5)
                if rng.random() < 0.5:
                    while not view.refilter_step(0.01):
                        pass
            timeline.sync(0.0005 if rng.random() < 0.3 else None)
        while not view.refilter_step(0.01):
            pass
        while not timeline.sync(0.001):
            pass
        for width in (1, 7, 80, 300):
            columns = timeline.columns(width)
            if not len(view):
                assert columns is None
                continue
            assert 1 <= len(columns) <= width
            # The columns span the records counted: the first and the last have some.
            assert columns.totals()[0] and columns.totals()[-1]
            counts, firsts = brute_columns(store, view, columns)
            assert counts == list(columns.counts)
            if store.evicted == 0:
                assert firsts == list(columns.first_seqs)
        histogram = timeline._histogram
        assert len(histogram.buckets) <= MAX_BUCKETS
        if histogram.buckets:  # the edges stepped in to the buckets left, no further
            assert (histogram.low, histogram.high) == (min(histogram.buckets), max(histogram.buckets))


def test_the_span_starts_again_when_every_record_counted_went():
    store = LogStore(max_messages=100)
    view = LogView(store)
    timeline = Timeline(store, view)
    store.extend_records(rec(i * 10 * S) for i in range(100))  # 0 to 990 s
    view.update()
    timeline.sync()
    store.extend_records(rec(500 * S + i * S // 10) for i in range(100))  # every record before goes
    view.update()
    timeline.sync()
    columns = timeline.columns(100)
    assert sum(columns.totals()) == 100
    assert columns.oldest_ns >= 499 * S and columns.newest_ns <= 511 * S
    assert columns.totals()[0] and columns.totals()[-1]


def test_a_long_history_widens_its_buckets():
    store = LogStore()
    view = LogView(store)
    timeline = Timeline(store, view)
    for day in range(40):
        store.extend_records(rec(day * 86_400 * S + i * S) for i in range(100))
        view.update()
        timeline.sync()
    assert timeline.bucket_ns >= 60 * S
    columns = timeline.columns(120)
    assert sum(columns.totals()) == 4000
    assert brute_columns(store, view, columns)[0] == list(columns.counts)


def test_node_stats_against_brute_force():
    rng = random.Random(5)
    for max_messages in (50, 10_000):
        store = LogStore(max_messages=max_messages)
        stats = NodeStats(store, window_s=60)
        stamp = 1000 * S
        for _ in range(10):
            batch = []
            for _ in range(rng.randint(1, 200)):
                stamp += rng.randint(0, 2 * S)
                batch.append(rec(stamp, level=rng.choice([10, 20, 30, 40, 50, 25]), node=rng.choice(["a", "b", "c"])))
            store.extend_records(batch)
            stats.update()
        records = list(store)
        newest = max(r.stamp_ns for r in records) // S
        oldest = min(r.stamp_ns for r in records) // S
        window = min(60, newest - oldest + 1)
        for entry in stats.nodes():
            mine = [r for r in records if r.node == entry.node]
            want = [sum(1 for r in mine if SLOT[r.level - r.level % 10] == slot) for slot in range(5)]
            assert list(entry.counts) == want
            recent = sum(1 for r in mine if r.stamp_ns // S > newest - 60)
            assert abs(entry.rate - recent / window) < 1e-9
        assert stats.window_seconds() == window
        assert sum(e.total for e in stats.nodes()) == len(store)
        busiest = stats.busiest(2)
        assert [e.rate for e in busiest] == sorted((e.rate for e in busiest), reverse=True)


def brute_node_counts(store):
    counts = {}
    for r in store:
        slots = counts.setdefault(r.node, [0] * 5)
        slots[SLOT[r.level - r.level % 10]] += 1
    return counts


def test_node_stats_count_only_when_asked_and_in_budgeted_steps():
    """Records are counted when ``sync`` is called, a chunk at a time until the budget is
    spent; those the store dropped before being counted are never taken off."""
    ticks = iter(range(10**6))
    store = LogStore(max_messages=3 * CHUNK_SIZE)
    stats = NodeStats(store, clock=lambda: next(ticks))
    store.extend_records(
        rec(i * S, level=(10, 20, 30, 40, 50)[i % 5], node="ab"[i % 2]) for i in range(CHUNK_SIZE + 10)
    )
    assert stats.nodes() == [] and not stats.counted  # nothing counted before asked
    assert stats.sync(budget_s=1) is False  # one chunk's worth: the clock moved by 1
    assert sum(e.total for e in stats.nodes()) == CHUNK_SIZE
    assert stats.sync(budget_s=1) is True
    assert {e.node: list(e.counts) for e in stats.nodes()} == brute_node_counts(store)
    # The store drops records never counted: the counts only lose what they had.
    store.extend_records(rec((10**5 + i) * S, node="c") for i in range(3 * CHUNK_SIZE))
    assert {e.node: list(e.counts) for e in stats.nodes() if e.total} == {}
    stats.update()
    assert (
        {e.node: list(e.counts) for e in stats.nodes()}
        == brute_node_counts(store)
        == {"c": [0, 3 * CHUNK_SIZE, 0, 0, 0]}
    )
    assert stats.nodes()[0].rate == 1.0  # one a second over the last minute


def test_first_of_a_severity_and_of_a_node():
    store = LogStore(max_messages=10_000)
    store.extend_records(rec(i, level=20, node="a") for i in range(9000))
    store.extend_records([rec(9000, level=45, node="b"), rec(9001, level=50, node="c"), rec(9002, level=40, node="b")])
    stats = NodeStats(store)
    stats.update()
    assert stats.first_of(40) == 9000
    assert stats.first_of(50) == 9001
    assert stats.first_of(30) is None
    assert stats.first_of_node(store.nodes.id_of("b")) == 9000
    assert find_level(store, 0, store.end_seq, *severity_range(40), last=True) == 9002
    assert find_level(store, 0, store.end_seq, *severity_range(30, or_worse=True)) == 9000
    assert find_node(store, 9001, store.end_seq, store.nodes.id_of("b")) == 9002
    assert severity_range(10) == (0, 19) and severity_range(50) == (50, 255)


def test_counting_again_after_a_rule_change_gives_what_counting_as_they_arrived_gave():
    """Counting again starts at the bucket width the shown records need (no merging on the
    way): the same width and counts as when the same records arrived one batch at a time,
    with a chunk whose stamps are out of order among them."""
    rng = random.Random(5)
    stamps = [i * 7 * S // 10 for i in range(3 * CHUNK_SIZE)]
    stamps[CHUNK_SIZE + 5], stamps[CHUNK_SIZE + 900] = stamps[CHUNK_SIZE + 900], stamps[CHUNK_SIZE + 5]
    records = [rec(stamp, level=rng.choice([10, 20, 30, 40])) for stamp in stamps]
    rules = RuleSet((exclude(SeverityRule.of("debug")),))
    arrived_store = LogStore()
    arrived_view = LogView(arrived_store, rules)
    arrived = Timeline(arrived_store, arrived_view)
    for at in range(0, len(records), 100):
        arrived_store.extend_records(records[at : at + 100])
        arrived_view.update()
        arrived.sync()
    store = LogStore()
    store.extend_records(records)
    view = LogView(store)
    timeline = Timeline(store, view)
    assert timeline.sync()
    view.set_rules(rules)
    while not view.refilter_step(0.01):
        pass
    assert timeline.sync()
    assert timeline.bucket_ns == arrived.bucket_ns > S
    assert timeline.total == arrived.total == len(view)
    for width in (100, 1000):
        columns = timeline.columns(width)
        assert columns == arrived.columns(width)
        assert brute_columns(store, view, columns) == (list(columns.counts), list(columns.first_seqs))


def test_followers_synced_together_end_as_synced_one_by_one():
    """The storms and the timeline caught up in one pass (``sync_together``), also from
    different places and in small steps, count what each counts on its own."""
    records = [
        rec(i * S // 100, level=(10, 20, 20, 30)[i % 4], node="ab"[i % 2], msg=f"m{i // 40}") for i in range(9000)
    ]
    results = []
    for together in (False, True):
        store = LogStore()
        store.extend_records(records)
        view = LogView(store, RuleSet((exclude(SeverityRule.of("debug")),)))
        while not view.refilter_step(0.01):
            pass
        storms, timeline = StormRows(store, view), Timeline(store, view)
        if together:
            assert not storms.sync(0.0)  # a chunk on: the two are at different places
            while not sync_together((storms, timeline), 0.0):
                pass
        else:
            assert storms.sync() and timeline.sync()
        results.append(([storms.seq_at(r) for r in range(len(storms))], storms.storm_count, timeline.columns(50)))
    assert results[0] == results[1]
    assert results[0][1] > 0
