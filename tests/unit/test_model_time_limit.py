"""Abandoning matching that runs too long: ``time_limit`` and the view's switched-off rules."""

from __future__ import annotations

import re
import signal
import threading
import time

import pytest

from console_tui.model.rules import MessageRule, RuleSet, SeverityRule, exclude, highlight
from console_tui.model.rules.pattern_match import MatchTimeout, TextMatch, time_limit
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView

CATASTROPHIC = r"(a+)+$"
HOSTILE = "a" * 30 + "b"  # (a+)+$ backtracks 2**30 ways on it: minutes in one re.search


def test_a_catastrophic_search_is_abandoned():
    with pytest.raises(MatchTimeout), time_limit(0.1):  # raised: abandoned, not run for minutes
        re.search(CATASTROPHIC, HOSTILE)


def test_work_within_the_limit_is_untouched_and_leaves_the_timer_as_it_was():
    handler = signal.getsignal(signal.SIGALRM)
    before, _ = signal.getitimer(signal.ITIMER_REAL)  # pytest-timeout's, if it uses signals
    with time_limit(0.5):
        assert re.search("b", HOSTILE)
    after, _ = signal.getitimer(signal.ITIMER_REAL)
    assert signal.getsignal(signal.SIGALRM) is handler
    assert after == 0.0 if before == 0.0 else before - 0.1 < after <= before
    time.sleep(0.6)  # no late alarm of ours


def test_an_earlier_timer_and_its_handler_are_kept():
    fired = []
    previous = signal.signal(signal.SIGALRM, lambda *_: fired.append(time.perf_counter()))
    try:
        began = time.perf_counter()
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        with time_limit(0.05):
            pass
        assert signal.getsignal(signal.SIGALRM) is not None and not fired
        remaining, _ = signal.getitimer(signal.ITIMER_REAL)
        assert 0 < remaining <= 0.3
        time.sleep(0.5)
        assert len(fired) == 1 and fired[0] - began >= 0.25
        # An earlier timer falling due inside the limit fires then, and the limit still holds.
        fired.clear()
        signal.setitimer(signal.ITIMER_REAL, 0.05)
        with pytest.raises(MatchTimeout), time_limit(0.2):
            re.search(CATASTROPHIC, HOSTILE)
        assert len(fired) == 1
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def test_off_the_main_thread_the_limit_is_checked_afterwards():
    outcome = []

    def run() -> None:
        try:
            with time_limit(0.01):
                time.sleep(0.05)
        except MatchTimeout:
            outcome.append("late")

    thread = threading.Thread(target=run)
    thread.start()
    thread.join()
    assert outcome == ["late"]


def test_text_match_mask_is_the_safe_entry_point():
    match = TextMatch(CATASTROPHIC, regex=True)
    assert match.mask(["aaa", "b"]) == b"\x01\x00"
    with pytest.raises(MatchTimeout):
        match.mask(["x", HOSTILE], limit_s=0.1)


def _store(msgs: list[str]) -> LogStore:
    store = LogStore()
    store.extend_records(LogRecord(stamp_ns=i, level=20 + 10 * (i % 2), node="n", msg=m) for i, m in enumerate(msgs))
    return store


def test_a_too_slow_rule_is_switched_off_and_the_others_stay():
    store = _store(["ok"] * 50 + [HOSTILE] + ["ok"] * 50)
    view = LogView(store, rule_limit_s=0.1)
    slow = MessageRule(CATASTROPHIC, regex=True)
    rules = RuleSet((exclude(SeverityRule.of("info")), highlight(slow)))
    view.set_rules(rules)
    while not view.refilter_step(0.01):  # ends: the slow rule is switched off, not run for minutes
        pass
    switched = view.take_switched_off()
    assert [rule for rule, _ in switched] == [slow]
    assert "too slow" in switched[0][1]
    assert view.rules.entries[1].enabled is False and view.rules.entries[0].enabled
    assert len(view) == 50  # the severity rule still applies
    assert view.take_switched_off() == []


def test_a_too_slow_rule_on_arrival_is_switched_off():
    store = _store(["ok"] * 10)
    view = LogView(store, rule_limit_s=0.1)
    slow = MessageRule(CATASTROPHIC, regex=True)
    view.set_rules(RuleSet((exclude(slow),)))
    assert len(view) == 10 and not view.switched_off
    store.append(LogRecord(stamp_ns=99, level=20, node="n", msg=HOSTILE))
    view.update()
    assert [rule for rule, _ in view.take_switched_off()] == [slow]
    assert len(view) == 11 and not view.filtered


def test_stop_filtering_switches_off_only_the_rules_being_applied():
    store = _store([f"message {i}" for i in range(20_000)])
    view = LogView(store)
    kept = exclude(SeverityRule.of("info"))
    view.set_rules(RuleSet((kept,)))
    while not view.refilter_step(1.0):
        pass
    assert view.stop_filtering() == []  # nothing is being applied
    new = MessageRule("message 1")
    view.set_rules(view.rules.add(exclude(new)), first_screen=10)
    assert view.refiltering
    assert view.stop_filtering() == [new]
    assert [entry.enabled for entry in view.rules.entries] == [True, False]
    while not view.refilter_step(1.0):
        pass
    assert len(view) == 10_000


def test_a_too_slow_rule_in_a_stream_is_switched_off():
    from console_tui.model.rules.stream import StreamFilter

    slow = MessageRule(CATASTROPHIC, regex=True)
    stream = StreamFilter(RuleSet((exclude(slow), exclude(MessageRule("hide me")))), rule_limit_s=0.1)
    batch = [LogRecord(stamp_ns=i, level=20, node="n", msg=m) for i, m in enumerate([HOSTILE, "hide me", "ok"])]
    assert [record.msg for record, _ in stream.filter(batch)] == [HOSTILE, "ok"]
    assert [rule for rule, _ in stream.switched_off] == [slow]
    assert [record.msg for record, _ in stream.filter(batch)] == [HOSTILE, "ok"]
