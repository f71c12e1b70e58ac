"""The model behind finding your way: marks, level and node toggles (rules underneath),
and the Time column's formats."""

from __future__ import annotations

import pytest

from console_tui.model.rules import key_rules
from console_tui.model.rules.message import MessageRule
from console_tui.model.rules.ruleset import RuleSet, exclude
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.time_column import TimeFormat, offset_text, sim_time_note, time_cell
from console_tui.model.view.log_view import LogView
from console_tui.model.view.marks import Marks

# -- marks ------------------------------------------------------------------------------------


def test_marks_toggle_jump_and_trim():
    marks = Marks()
    for seq in (50, 10, 30):
        assert marks.toggle(seq)
    assert list(marks) == [10, 30, 50] and 30 in marks
    assert not marks.toggle(30) and 30 not in marks
    assert marks.nearest(10, forward=True, shown=lambda s: True) == 50
    assert marks.nearest(50, forward=False, shown=lambda s: s != 10) is None
    assert marks.nearest(0, forward=True, shown=lambda s: True) == 10
    marks.trim(20)
    assert list(marks) == [50]


# -- level and node toggles -------------------------------------------------------------------


def record(level: int, node: str = "talker") -> LogRecord:
    return LogRecord(stamp_ns=0, level=level, node=node, msg="m")


def shown_levels(rules: RuleSet) -> list[int]:
    return [level for level in (10, 20, 30, 40, 50) if rules.verdict(record(level))[0]]


def test_level_toggles_are_one_rule_in_the_rule_set():
    rules = RuleSet((exclude(MessageRule("noise")),))
    rules = key_rules.toggle_level(rules, 20)
    assert shown_levels(rules) == [10, 30, 40, 50]
    assert key_rules.levels_text(rules) == "hiding INFO"
    rules = key_rules.raise_minimum(rules)  # above DEBUG, the lowest shown: INFO stays hidden
    assert shown_levels(rules) == [30, 40, 50] and key_rules.levels_text(rules) == "level≥WARN"
    assert len(rules.entries) == 2 and rules.entries[1].toggle == key_rules.LEVELS
    assert rules.entries[1].describe() == "severity DEBUG, INFO"
    rules = key_rules.lower_minimum(rules)
    assert key_rules.levels_text(rules) == "level≥INFO"
    for _ in range(6):
        rules = key_rules.raise_minimum(rules)
    assert shown_levels(rules) == [50]
    rules = key_rules.with_hidden_levels(rules, frozenset())
    assert key_rules.levels_text(rules) == "" and len(rules.entries) == 1
    # The rules pane switches the levels rule off: every level shows, and the keys go on from there.
    rules = key_rules.with_minimum(rules, 40)
    rules = rules.with_enabled(1, False)
    assert key_rules.hidden_levels(rules) == frozenset() and shown_levels(rules) == [10, 20, 30, 40, 50]
    rules = key_rules.toggle_level(rules, 10)
    assert shown_levels(rules) == [20, 30, 40, 50] and len(rules.entries) == 2


def test_the_minimum_level_and_the_level_toggles_compose():
    rules = key_rules.toggle_level(RuleSet(), 30)  # WARN hidden on its own
    rules = key_rules.raise_minimum(rules)
    assert shown_levels(rules) == [20, 40, 50] and key_rules.levels_text(rules) == "level≥INFO, hiding WARN"
    rules = key_rules.raise_minimum(rules)  # past WARN, hidden already: to ERROR
    assert shown_levels(rules) == [40, 50] and key_rules.levels_text(rules) == "level≥ERROR"
    rules = key_rules.lower_minimum(rules)
    assert shown_levels(rules) == [30, 40, 50]
    rules = key_rules.toggle_level(key_rules.toggle_level(RuleSet(), 40), 10)
    assert key_rules.levels_text(rules) == "level≥INFO, hiding ERROR"
    rules = key_rules.lower_minimum(rules)  # DEBUG again, ERROR still hidden
    assert shown_levels(rules) == [10, 20, 30, 50] and key_rules.levels_text(rules) == "hiding ERROR"
    rules = key_rules.with_hidden_levels(RuleSet(), frozenset({10, 20, 30, 40}))
    assert key_rules.raise_minimum(rules) == rules  # FATAL, the last shown, stays


def test_solo_and_mute_are_exact_and_exclusive():
    rules = RuleSet()
    rules = key_rules.toggle_solo(rules, "nav.plan[1]*")
    assert rules.verdict(record(20, "nav.plan[1]*"))[0]
    assert not rules.verdict(record(20, "nav.plan1x"))[0]
    assert key_rules.nodes_text(rules) == "solo nav.plan[1]*"
    rules = key_rules.toggle_solo(rules, "/talker")  # a ROS 1 node name
    assert rules.verdict(record(20, "/talker"))[0] and key_rules.nodes_text(rules) == "solo 2 nodes"
    rules = key_rules.toggle_mute(rules, "/talker")
    assert key_rules.soloed(rules) == ("nav.plan[1]*",) and key_rules.muted(rules) == ("/talker",)
    assert key_rules.nodes_text(rules) == "solo nav.plan[1]*, muted /talker"
    rules = key_rules.toggle_solo(rules, "nav.plan[1]*")
    assert key_rules.soloed(rules) == () and not rules.verdict(record(20, "/talker"))[0]
    assert rules.verdict(record(20, "other"))[0]
    assert key_rules.without_node_toggles(rules).entries == ()


# -- time formats -----------------------------------------------------------------------------

STAMP = 1_700_000_000_123_456_789


@pytest.mark.parametrize(
    ("fmt", "expected"),
    [
        (TimeFormat.CLOCK, "22:13:20.123"),
        (TimeFormat.DATE, "2023-11-14 22:13:20.123"),
        (TimeFormat.STAMP, "1700000000.123456789"),
        (TimeFormat.SINCE_FIRST, "+1:01:01.000"),
        (TimeFormat.SINCE_ROW, "+1:01:01.000"),
        (TimeFormat.DELTA, "+0.500"),
    ],
)
def test_time_cells(fmt, expected):
    origin = STAMP - 3_661_000_000_000
    assert time_cell(STAMP, fmt, utc=True, origin_ns=origin, previous_ns=STAMP - 500_000_000) == expected


def test_durations_and_sim_time():
    assert offset_text(0) == "0.000"
    assert offset_text(-1_500_000_000) == "-1.500"
    assert offset_text(61_000_000_000) == "+1:01.000"
    assert offset_text(2 * 86_400_000_000_000 + 5_000_000_000) == "+2d 00:00:05"
    assert time_cell(STAMP, TimeFormat.DELTA, previous_ns=None) == ""
    now = STAMP
    assert "near 0" in sim_time_note(12_000_000_000, now, live=False)
    assert sim_time_note(STAMP - 400 * 86_400 * 10**9, now, live=False) == ""  # an old file
    assert "far" in sim_time_note(STAMP - 400 * 86_400 * 10**9, now, live=True)
    assert "far" in sim_time_note(STAMP + 3 * 86_400 * 10**9, now, live=False)
    assert sim_time_note(STAMP, now, live=True) == ""


def test_view_shows_only_rows_the_rules_let_through():
    from console_tui.model.view.seek import view_shows

    store = LogStore()
    store.extend_records([record(20), record(40), record(20)])
    view = LogView(store, key_rules.with_minimum(RuleSet(), 40))
    assert [view_shows(view, seq) for seq in range(4)] == [False, True, False, False]
