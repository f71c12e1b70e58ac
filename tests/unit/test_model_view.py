"""The row index over the store: identity without rules, rules applied on arrival, eviction,
incremental refiltering newest first, decorations and match counts."""

import random

import pytest

from console_tui.model.rules import (
    MessageRule,
    NodeRule,
    RuleSet,
    SeverityRule,
    exclude,
    highlight,
)
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView

from support.clock import TickingClock

WARN_AND_ABOVE = RuleSet((exclude(SeverityRule.of("debug", "info")),))


def fill(store, n, start=0):
    store.extend_records(
        LogRecord(stamp_ns=i, level=10 * (1 + i % 5), node=f"n{i % 7}", msg=f"m{i} {'x' * (i % 3)}")
        for i in range(start, start + n)
    )


def rows(view):
    return [view.seq_at(r) for r in range(len(view))]


def expected(store, rules):
    """Everything at once: each active rule over whole spans, then ``RuleSet.decide``."""
    shown, marks = [], {}
    tests = {rule: rule.compile(store) for rule in rules.active_rules()}
    for chunk, lo, hi, seq in store.spans(store.first_seq, store.end_seq):
        masks = {rule: test(chunk, lo, hi) for rule, test in tests.items()}
        visible, highlighted = rules.decide(masks, hi - lo)
        for offset in range(hi - lo):
            if visible[offset]:
                shown.append(seq + offset)
                if rules.highlighting:
                    marks[seq + offset] = "highlight" if highlighted[offset] else "dim"
                else:
                    marks[seq + offset] = None
    return shown, marks


def check(view, store, rules):
    shown, marks = expected(store, rules)
    assert rows(view) == shown
    assert {seq: view.decoration_of(seq) for seq in shown} == marks
    for row, seq in enumerate(shown):
        assert view.row_of(seq) == row


def finish(view):
    steps = 0
    while not view.refilter_step(0.001):
        steps += 1
    return steps


def test_unfiltered_rows_are_all_records():
    store = LogStore(max_messages=10)
    view = LogView(store)
    fill(store, 15)
    assert len(view) == 10 and view.seq_at(0) == 5 and view.row_of(7) == 2
    assert not view.filtered and view.decoration_of(7) is None


def test_filtered_rows_extend_and_trim():
    store = LogStore(max_messages=20)
    view = LogView(store, WARN_AND_ABOVE)
    fill(store, 10)
    view.update()
    assert rows(view) == [2, 3, 4, 7, 8, 9]
    fill(store, 20, start=10)
    view.update()
    assert view.seq_at(0) == 12 and len(view) == 12
    assert view.row_of(13) == 1 and view.row_of(15) == 3
    with pytest.raises(IndexError):
        view.seq_at(12)


def test_new_records_are_tested_once():
    store = LogStore()
    fill(store, 100)
    calls = []
    rule = SeverityRule.of("warn")
    view = LogView(store, RuleSet((exclude(rule),)))
    finish(view)
    test = view._tests[rule]
    view._tests[rule] = lambda chunk, lo, hi: calls.append(hi - lo) or test(chunk, lo, hi)
    fill(store, 50, start=100)
    view.update()
    view.update()
    assert calls == [50]


def test_refilter_newest_first_with_first_screen_at_once():
    store = LogStore()
    fill(store, 5 * CHUNK_SIZE + 100)
    # Each clock reading is 1 ms later: the first screen fits the 30 ms budget and a 1 ms step
    # does one piece, however fast or busy the machine is.
    view = LogView(store)
    view.clock = TickingClock(0.001)
    rules = RuleSet((exclude(MessageRule("x")),))
    view.set_rules(rules, first_screen=50)
    assert view.refiltering and 50 <= len(view) < len(store)
    shown, _ = expected(store, rules)
    # The rows so far are exactly the newest of the final rows.
    assert rows(view) == shown[-len(view) :]
    assert finish(view) >= 1  # more than one step
    check(view, store, rules)
    assert not view.refiltering and view.pending == 0


@pytest.mark.parametrize("seed", range(4))
def test_arrivals_and_eviction_during_refilter(seed):
    rng = random.Random(seed)
    store = LogStore(max_messages=3 * CHUNK_SIZE)
    fill(store, 3 * CHUNK_SIZE)
    view = LogView(store)
    rules = RuleSet((exclude(NodeRule(("n1", "n2"))), highlight(MessageRule("xx"))))
    view.set_rules(rules, first_screen=10, budget_s=0)
    added = len(store) + store.evicted
    while view.refiltering:
        count = rng.randrange(0, 900)
        fill(store, count, start=added)
        added += count
        view.update()
        view.refilter_step(0.0005)
        shown, _ = expected(store, rules)
        assert rows(view) == shown[len(shown) - len(view) :]
    check(view, store, rules)
    assert store.evicted > 0


def test_everything_evicted_during_refilter_ends_it():
    store = LogStore(max_messages=2 * CHUNK_SIZE)
    fill(store, 2 * CHUNK_SIZE)
    view = LogView(store)
    view.set_rules(WARN_AND_ABOVE, first_screen=1, budget_s=0)
    fill(store, 3 * CHUNK_SIZE, start=2 * CHUNK_SIZE)
    view.update()
    assert not view.refiltering
    check(view, store, WARN_AND_ABOVE)


def test_decorations_dim_rows_not_highlighted_only_while_highlighting():
    store = LogStore()
    fill(store, 40)
    rules = RuleSet((highlight(NodeRule(("n3",))),))
    view = LogView(store, rules)
    assert len(view) == 40 and not view.filtered and view.highlighting
    assert view.decoration_of(3) == "highlight" and view.decoration_of(4) == "dim"
    view.set_rules(rules.with_enabled(0, False))
    assert view.decoration_of(3) is None and len(view) == 40
    view.set_rules(rules.with_highlighted_only(True))
    finish(view)
    assert view.filtered and rows(view) == [3, 10, 17, 24, 31, 38]
    check(view, store, rules.with_highlighted_only(True))


def test_match_counts_per_entry_follow_arrivals_eviction_and_inversion():
    store = LogStore(max_messages=2 * CHUNK_SIZE)
    fill(store, 1000)
    rules = RuleSet(
        (
            exclude(SeverityRule.of("debug")),
            highlight(NodeRule(("n0",)), inverted=True),
            exclude(MessageRule("")),  # empty: not active
            exclude(SeverityRule.of("fatal"), enabled=False),
        )
    )
    view = LogView(store, rules)
    finish(view)

    def brute():
        kept = list(store)
        return [
            sum(r.level == 10 for r in kept),
            sum(r.node != "n0" for r in kept),
            None,
            None,
        ]

    assert view.match_counts() == brute()
    fill(store, 3 * CHUNK_SIZE, start=1000)
    view.update()
    assert store.evicted and view.match_counts() == brute()


def test_toggling_an_entry_reuses_masks():
    store = LogStore()
    fill(store, 3000)
    rule = MessageRule("m1")
    rules = RuleSet((exclude(rule),))
    view = LogView(store, rules)
    finish(view)
    view._tests[rule] = None  # would fail if called again
    for changed in (rules.with_inverted(0, True), rules.with_role(0, rules.entries[0].role.HIGHLIGHT)):
        view._tests = {rule: view._tests[rule]}
        view.set_rules(changed)
        finish(view)
        check(view, store, changed)


def test_rebuild_after_clear():
    store = LogStore()
    fill(store, 100)
    view = LogView(store, WARN_AND_ABOVE)
    store.clear()
    view.rebuild()
    assert len(view) == 0 and not view.refiltering
    fill(store, 10, start=100)
    view.update()
    check(view, store, WARN_AND_ABOVE)
