"""Narrowing a loaded run down (issue 28), as a property: after any sequence of rule changes
(level toggles, ``>``/``<``, solo/mute, query edits, storms on and off), each applied around
a selected record while the last one is still being worked through, the rows, the storms, the
count of shown messages and the timeline's totals equal those computed from scratch under the
final rules; and the rows around the selected record are decided at once."""

from __future__ import annotations

import os
from functools import cache
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from console_tui.model.formats.rosout_log import parse_rosout_record
from console_tui.model.overview.storms import StormRows
from console_tui.model.overview.timeline import Timeline
from console_tui.model.rules import key_rules
from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import RuleSet
from console_tui.model.store.log_store import LogStore
from console_tui.model.view.log_view import LogView

from support.storm_log import write_storm_log

NODES = ["/talker", "/listener", "/planner"]
QUERIES = ["", "burst", "heard 1", "-failed", "level>=warn", "node:/talker,/planner", "/burst [0-9]+0,/", "+plan"]


@cache
def loaded_store() -> LogStore:
    """The 20,213 records of the storm log (``support.storm_log``), read as the loader reads them."""
    path = Path(__file__).with_name(".narrowing-rosout.log")
    try:
        write_storm_log(path)
        records = [parse_rosout_record(line, "rosout.log") for line in path.read_text().splitlines()]
    finally:
        path.unlink(missing_ok=True)
    store = LogStore()
    store.extend_records(records)
    return store


def rows_of(rows) -> list[int]:
    return [rows.seq_at(row) for row in range(len(rows))]


def from_scratch(store: LogStore, rules: RuleSet, storms_on: bool):
    view = LogView(store, rules)
    while not view.refilter_step(1.0):
        pass
    storms = StormRows(store, view, enabled=storms_on)
    timeline = Timeline(store, view)
    assert storms.sync() and timeline.sync()
    return view, storms, timeline


def apply(rules: RuleSet, op: tuple) -> RuleSet:
    kind, arg = op
    if kind == "level":
        return key_rules.toggle_level(rules, arg)
    if kind == "raise":
        return key_rules.raise_minimum(rules)
    if kind == "lower":
        return key_rules.lower_minimum(rules)
    if kind == "solo":
        return key_rules.toggle_solo(rules, arg)
    if kind == "mute":
        return key_rules.toggle_mute(rules, arg)
    if kind == "query":
        return rules.with_query(parse_query(arg, utc=True))
    return rules


OPS = st.one_of(
    st.tuples(st.just("level"), st.sampled_from([10, 20, 30, 40, 50])),
    st.tuples(st.sampled_from(["raise", "lower", "storms"]), st.none()),
    st.tuples(st.sampled_from(["solo", "mute"]), st.sampled_from(NODES)),
    st.tuples(st.just("query"), st.sampled_from(QUERIES)),
)


@settings(
    max_examples=int(os.environ.get("NARROWING_EXAMPLES", "25")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
@given(
    ops=st.lists(st.tuples(OPS, st.integers(0, 4), st.floats(0, 1)), min_size=1, max_size=8),
    selected=st.integers(0, 20_212),
)
def test_any_rule_changes_end_where_the_final_rules_computed_afresh_do(ops, selected):
    store = loaded_store()
    view = LogView(store)
    storms = StormRows(store, view)
    timeline = Timeline(store, view)
    assert storms.sync() and timeline.sync()
    rules = RuleSet()
    for op, steps, where in ops:
        if op[0] == "storms":
            storms.set_enabled(not storms.enabled)
        else:
            rules = apply(rules, op)
            # Around a record shown now (the table's selected row), or the newest (following).
            around = view.seq_at(int(where * (len(view) - 1))) if where < 0.9 and len(view) else None
            view.set_rules(rules, around=around, budget_s=60.0)  # a first screen however slow the machine
            if around is not None and view.rules.filtering:
                # The rows around it are decided at once: its row, and the rows each side of it.
                row = view.row_of(around)
                shown = rows_of(LogView(store, rules))  # ... as the rules decide them afresh
                at = shown.index(around) if around in shown else None
                if at is not None:
                    assert view.seq_at(row) == around
                    lo, hi = max(at - 20, 0), min(at + 20, len(shown))
                    assert [view.seq_at(row - at + i) for i in range(lo, hi)] == shown[lo:hi]
        for _ in range(steps):  # part of the work done before the next change (a piece each)
            view.refilter_step(0.0)
            storms.sync(0.0)
            timeline.sync(0.0)
    while not view.refilter_step(1.0):
        pass
    assert storms.sync() and timeline.sync()
    fresh_view, fresh_storms, fresh_timeline = from_scratch(store, view.rules, storms.enabled)
    assert rows_of(view) == rows_of(fresh_view)
    assert len(view) == len(fresh_view)  # the status line's "N/20,213 shown"
    assert rows_of(storms) == rows_of(fresh_storms)
    assert storms.storm_count == fresh_storms.storm_count
    assert [storms.badge(seq) for seq in rows_of(storms)] == [fresh_storms.badge(seq) for seq in rows_of(fresh_storms)]
    assert timeline.total == fresh_timeline.total == len(fresh_view)
    columns, fresh_columns = timeline.columns(100), fresh_timeline.columns(100)
    assert (columns and columns.totals()) == (fresh_columns and fresh_columns.totals())


def counted(storms: StormRows, timeline: Timeline) -> tuple:
    columns = timeline.columns(100)
    badges = [storms.badge(seq) for seq in rows_of(storms)]
    return rows_of(storms), storms.storm_count, badges, timeline.total, columns and columns.totals()


def test_back_to_every_record_shown_takes_back_the_counts_and_counts_only_what_arrived():
    store = LogStore()
    store.extend_records(list(loaded_store())[:5000])
    view = LogView(store)
    storms, timeline = StormRows(store, view), Timeline(store, view)
    assert storms.sync() and timeline.sync()
    hidden = key_rules.toggle_level(RuleSet(), 20)
    for arrive in (0, 300):
        view.set_rules(hidden)
        while not view.refilter_step(1.0):
            pass
        assert storms.sync() and timeline.sync()
        before = store.end_seq
        store.extend_records(list(loaded_store())[before : before + arrive])  # arrived while INFO was hidden
        view.update()
        assert storms.sync() and timeline.sync()
        view.set_rules(RuleSet())
        storms.follow_rules(), timeline.follow_rules()
        assert storms.done_to == timeline.done_to == before  # only what arrived is still to take in
        assert storms.sync() and timeline.sync()
        assert counted(storms, timeline) == counted(*from_scratch(store, view.rules, True)[1:])


def test_highlight_rules_count_nothing_again_and_records_dropped_meanwhile_mean_a_recount():
    store = LogStore(max_messages=6000)
    store.extend_records(list(loaded_store())[:5000])
    view = LogView(store)
    storms, timeline = StormRows(store, view), Timeline(store, view)
    assert storms.sync() and timeline.sync()
    view.set_rules(RuleSet().with_query(parse_query("+burst", utc=True)))  # highlights only
    assert storms.sync(0.0) and timeline.sync(0.0) and not storms.rebuilding
    view.set_rules(key_rules.toggle_level(view.rules, 20))
    while not view.refilter_step(1.0):
        pass
    assert storms.sync() and timeline.sync()
    store.extend_records(list(loaded_store())[5000:7000])  # 1,000 of the oldest go
    view.update()
    assert storms.sync() and timeline.sync()
    view.set_rules(RuleSet())
    storms.follow_rules()
    assert storms.done_to == store.first_seq  # counted again from the oldest kept
    assert storms.sync() and timeline.sync()
    assert counted(storms, timeline) == counted(*from_scratch(store, view.rules, True)[1:])
