"""Storms collapsed (``StormRows``): runs of one node's repeats as one row, against a
brute-force reading of the shown rows, as records arrive, under rules, with eviction,
expanded and collapsed, with digits masked."""

import random

from console_tui.model.overview.storms import StormRows, mask_digits
from console_tui.model.rules import NodeRule, RuleSet, SeverityRule, exclude
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView


def rec(i, node="a", msg="same", level=20, source=""):
    return LogRecord(stamp_ns=1_000_000_000 * i, level=level, node=node, msg=msg, source=source)


def storm_rows(records=()) -> tuple[LogStore, LogView, StormRows]:
    """A store holding ``records``, its view and their storm rows (not synced yet)."""
    store = LogStore()
    store.extend_records(records)
    view = LogView(store)
    return store, view, StormRows(store, view)


def rows_of(rows):
    return [rows.seq_at(r) for r in range(len(rows))]


def expected(store, view, masked=False, expanded_heads=()):
    """Runs per node over the shown rows, from scratch: (rows, {head: (count, last)})."""
    shown = [view.seq_at(r) for r in range(len(view))]
    runs = {}
    heads = {}
    members = {}
    out = []
    for seq in shown:
        record = store.get(seq)
        key = (record.level, record.source, mask_digits(record.msg) if masked else record.msg)
        run = runs.get(record.node)
        if run is not None and run[1] == key:
            heads[run[0]][0] += 1
            heads[run[0]][1] = seq
            members.setdefault(run[0], []).append(seq)
        else:
            runs[record.node] = (seq, key)
            heads[seq] = [1, seq]
            out.append(seq)
    for head in expanded_heads:
        out.extend(members.get(head, []))
    out.sort()
    return out, {head: tuple(v) for head, v in heads.items() if v[0] >= 2}


def check(store, view, rows, masked=False, expanded_heads=()):
    assert rows.sync()
    want_rows, want_storms = expected(store, view, masked, expanded_heads)
    assert rows_of(rows) == want_rows
    for row, seq in enumerate(want_rows):
        assert rows.row_of(seq) == row
    got = {}
    for seq in want_rows:
        badge = rows.badge(seq)
        if badge is not None and badge.head:
            got[seq] = (badge.repeats, badge.last)
    assert got == want_storms


def test_ten_thousand_identical_messages_are_one_row():
    *_, rows = storm_rows(rec(i) for i in range(10_000))
    assert rows.sync()
    assert len(rows) == 1
    badge = rows.badge(rows.seq_at(0))
    assert badge is not None and badge.repeats == 10_000 and badge.last == 9_999


def test_other_nodes_between_do_not_break_a_storm_another_text_does():
    *_, rows = storm_rows(
        [rec(0, "a", "x"), rec(1, "b", "y"), rec(2, "a", "x"), rec(3, "b", "z"), rec(4, "a", "x"), rec(5, "a", "w")]
    )
    assert rows.sync()
    assert rows_of(rows) == [0, 1, 3, 5]
    assert rows.badge(0) == (3, 0, 4, False, True)
    assert rows.badge(1) is None  # y then z: two messages on their own
    # A collapsed repeat shows in its storm's row: the row of seq 2 is the next row after it.
    assert rows.row_of(2) == 2


def test_severity_and_source_are_part_of_a_storm():
    store = LogStore()
    store.extend_records([rec(0, level=20), rec(1, level=30), rec(2, level=30), rec(3, level=30, source="rosout.log")])
    rows = StormRows(store, LogView(store))
    assert rows.sync()
    assert rows_of(rows) == [0, 1, 3]


def test_digits_masked_on_request():
    store, view, rows = storm_rows(rec(i, msg=f"took {i}.{i * 7} ms") for i in range(50))
    check(store, view, rows)
    assert len(rows) == 50
    rows.set_mask_digits(True)
    check(store, view, rows, masked=True)
    assert len(rows) == 1


def test_counts_exact_as_repeats_arrive():
    store, view, rows = storm_rows()
    for batch in range(20):
        store.extend_records(rec(batch * 500 + i, node="a" if i % 3 else "b", msg="x") for i in range(500))
        view.update()
        rows.sync()
        badge = rows.badge(1)  # node a's storm (b logs every third message)
        assert badge is not None and badge.repeats == sum(1 for s in range(store.end_seq) if (s % 500) % 3)
    check(store, view, rows)


def test_expand_and_collapse():
    store, view, rows = storm_rows(
        [rec(0, "a", "x"), rec(1, "b", "y"), rec(2, "a", "x"), rec(3, "b", "z"), rec(4, "a", "x")]
    )
    assert rows.sync()
    storm = rows.storm_of(0)
    assert storm is not None
    rows.expand(storm)
    assert rows_of(rows) == [0, 1, 2, 3, 4]
    assert rows.badge(0) == (3, 0, 4, True, True)
    assert rows.badge(2) == (3, 0, 4, True, False)
    # New repeats of an expanded storm are rows too.
    store.extend_records([rec(5, "a", "x")])
    view.update()
    rows.sync()
    assert rows_of(rows) == [0, 1, 2, 3, 4, 5]
    assert rows.storm_of(4) is storm
    rows.collapse(storm)
    assert rows_of(rows) == [0, 1, 3]
    assert rows.badge(0) == (4, 0, 5, False, True)


def test_off_shows_the_view():
    *_, rows = storm_rows(rec(i) for i in range(100))
    rows.sync()
    assert len(rows) == 1
    rows.set_enabled(False)
    assert len(rows) == 100 and rows.seq_at(42) == 42 and rows.badge(42) is None
    rows.set_enabled(True)
    assert len(rows) == 100  # not collapsed again yet: the view's rows meanwhile
    rows.sync()
    assert len(rows) == 1


def test_rows_not_caught_up_are_the_views():
    store, view, rows = storm_rows(rec(i) for i in range(10))
    rows.sync()
    store.extend_records(rec(i) for i in range(10, 15))
    view.update()
    assert rows_of(rows) == [0, 10, 11, 12, 13, 14]
    assert rows.row_of(12) == 3
    rows.sync()
    assert rows_of(rows) == [0]


def test_rules_change_collapses_again():
    store, view, rows = storm_rows([rec(0, "a", "x"), rec(1, "a", "y", level=10), rec(2, "a", "x")])
    check(store, view, rows)
    assert len(rows) == 3
    view.set_rules(RuleSet((exclude(SeverityRule.of("debug")),)))
    assert rows.sync()
    assert rows_of(rows) == [0]
    check(store, view, rows)


def test_random_histories_against_brute_force():
    rng = random.Random(7)
    nodes = ["a", "b", "c"]
    texts = ["x", "y", "took 1 ms", "took 22 ms"]
    for trial in range(40):
        store = LogStore(max_messages=rng.choice([50, 200, 5000]))
        view = LogView(store)
        masked = trial % 2 == 1
        rows = StormRows(store, view, mask_digits=masked)
        seq = 0
        for _step in range(rng.randint(3, 12)):
            batch = []
            for _ in range(rng.randint(1, 120)):
                burst = rng.random() < 0.7
                node = "a" if burst else rng.choice(nodes)
                text = "x" if burst else rng.choice(texts)
                source = "b.log" if rng.random() < 0.05 else ""
                batch.append(rec(seq, node, text, level=rng.choice([10, 20, 20, 30]), source=source))
                seq += 1
            store.extend_records(batch)
            view.update()
            if rng.random() < 0.2:
                rule = rng.choice([SeverityRule.of("debug"), NodeRule(("b",))])
                view.set_rules(RuleSet((exclude(rule),)), first_screen=5)
            if rng.random() < 0.5:  # else records arrive (and go) while the view still filters
                while not view.refilter_step(0.01):
                    pass
            rows.sync(0.001 if rng.random() < 0.3 else None)
        while not view.refilter_step(0.01):
            pass
        while not rows.sync(0.001):
            pass
        check(store, view, rows, masked=masked)
        # Expand one storm and check again, then collapse it.
        heads = [rows.seq_at(r) for r in range(len(rows)) if rows.badge(rows.seq_at(r))]
        if heads:
            head = rng.choice(heads)
            storm = rows.storm_of(head)
            rows.expand(storm)
            check(store, view, rows, masked=masked, expanded_heads=[head])
            store.extend_records([rec(seq, "a", "x", level=20)])
            view.update()
            rows.sync()
            rows.collapse(storm)
            check(store, view, rows, masked=masked)


def test_the_row_showing_a_collapsed_repeat_is_its_storms():
    _, view, rows = storm_rows(
        [rec(0, "a", "x"), rec(1, "b", "y"), rec(2, "a", "x"), rec(3, "b", "z"), rec(4, "c", "q", level=10)]
    )
    rows.sync()
    assert rows_of(rows) == [0, 1, 3, 4]
    assert rows.row_showing(2) == 0  # a's repeat: the storm's row
    assert rows.row_showing(3) == 2
    view.set_rules(RuleSet((exclude(SeverityRule.of("debug")),)))
    rows.sync()
    assert rows.row_showing(4) == 3  # hidden: the row after it (there is none)


def test_row_shown_is_the_storms_row_for_a_repeat_and_none_for_a_hidden_message():
    _, view, rows = storm_rows(
        [rec(0, "a", "x"), rec(1, "b", "y"), rec(2, "a", "x"), rec(3, "b", "z"), rec(4, "c", "q", level=10)]
    )
    rows.sync()
    assert [rows.row_shown(seq) for seq in range(5)] == [0, 1, 0, 2, 3]
    assert view.row_shown(2) == 2  # the view itself: every message its row
    view.set_rules(RuleSet((exclude(SeverityRule.of("debug")),)))
    while not view.refilter_step(0.01):
        pass
    rows.sync()
    assert rows.row_shown(4) is None and view.row_shown(4) is None
    rows.set_enabled(False)
    assert [rows.row_shown(seq) for seq in range(4)] == [0, 1, 2, 3]


def test_chunks_with_no_repeated_text_against_brute_force():
    """Full chunks where no two texts are the same (the storms take them in reading only each
    node's first text) and one where one node repeats a text (its records taken in apart
    from the others'): a repeat across a chunk's edge, rules and masked digits changed."""
    rng = random.Random(11)
    records = [rec(i, rng.choice("abc"), f"reading {i}", level=rng.choice([10, 20, 30])) for i in range(3 * CHUNK_SIZE)]
    edge = CHUNK_SIZE
    records[edge - 1] = rec(edge - 1, "z", "across the edge")
    records[edge] = rec(edge, "z", "across the edge")  # the first of the node "z" in the second chunk
    for i in range(2 * CHUNK_SIZE + 10, 2 * CHUNK_SIZE + 30):
        records[i] = rec(i, "a", "again")  # a storm: the third chunk's texts repeat
    store, view, rows = storm_rows(records)
    check(store, view, rows)
    assert rows.badge(edge - 1) == (2, edge - 1, edge, False, True)
    assert rows._facts and any(rows._facts.values()) and not all(rows._facts.values())
    for rules in (RuleSet((exclude(SeverityRule.of("debug")),)), RuleSet((exclude(NodeRule(("b",))),)), RuleSet()):
        view.set_rules(rules)
        while not view.refilter_step(0.01):
            pass
        check(store, view, rows)
    rows.set_mask_digits(True)  # "reading #" repeats now
    check(store, view, rows, masked=True)
