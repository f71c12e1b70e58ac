"""How the live source picks /rosout_agg over /rosout without showing a message twice."""

from __future__ import annotations

from console_tui.model.record import LogRecord
from console_tui.model.record_batch import RecordColumns
from console_tui.sources.ros2.topic_choice import AUTO_TOPIC_MAX_S, SWITCH_DEDUPE_S, TopicChoice


def records(node: str, *stamps: int) -> list[LogRecord]:
    return [LogRecord(stamp, 20, node, f"{node} {stamp}", source="") for stamp in stamps]


def taken(records: list[LogRecord]) -> RecordColumns:
    """A batch as the topic reader takes it."""
    return RecordColumns.from_records(records)


def passed(choice: TopicChoice, records: list[LogRecord], topic: str, now: float) -> list[LogRecord]:
    """What the choice lets on of ``records``, as records."""
    return choice.filter(taken(records), topic, now).records()


def test_held_at_start_then_released_in_order_without_an_aggregator():
    choice = TopicChoice(0.0)
    assert passed(choice, records("a", 1, 2), "/rosout", 0.1) == []
    assert passed(choice, records("a", 3), "/rosout", 1.0) == []
    released = passed(choice, [], "/rosout", AUTO_TOPIC_MAX_S + 0.1)
    assert [r.stamp_ns for r in released] == [1, 2, 3]
    assert [r.stamp_ns for r in passed(choice, records("a", 4), "/rosout", 9.0)] == [4]


def test_aggregator_found_at_start_drops_what_was_held():
    choice = TopicChoice(0.0)
    passed(choice, records("a", 5, 6), "/rosout", 0.5)
    choice.switched(1.0)
    history = records("a", 1, 2, 3, 4, 5, 6)
    assert passed(choice, history, "/rosout_agg", 1.1) == history


def test_aggregator_found_later_gives_only_what_was_not_seen():
    choice = TopicChoice(0.0)
    passed(choice, records("a", 1), "/rosout", 0.1)
    assert [r.stamp_ns for r in passed(choice, records("a", 2) + records("b", 7), "/rosout", 5.0)] == [1, 2, 7]
    choice.switched(10.0)
    history = records("a", 1, 2, 3) + records("b", 6, 7, 8) + records("c", 1)
    got = passed(choice, history, "/rosout_agg", 10.1)
    # b 6 is older than anything /rosout gave for b (it keeps only its last 10 s): kept too.
    assert [(r.node, r.stamp_ns) for r in got] == [("a", 3), ("b", 6), ("b", 8), ("c", 1)]
    later = records("a", 1)  # long after the switch, nothing is held against anything
    assert passed(choice, later, "/rosout_agg", 10.0 + SWITCH_DEDUPE_S + 1) == later


def test_holding_ends_once_the_publishers_found_have_settled():
    choice = TopicChoice(0.0)
    choice.publishers(0, 0.2)
    assert choice.holding(0.9)
    choice.publishers(2, 0.9)  # found two
    choice.publishers(2, 1.5)
    assert choice.holding(1.6)
    choice.publishers(3, 1.7)  # another one: wait again
    choice.publishers(3, 2.5)
    assert choice.holding(2.6)
    choice.publishers(3, 2.8)  # unchanged for a second
    assert not choice.holding(2.8)
    nothing = TopicChoice(0.0)
    for step in range(50):
        nothing.publishers(0, step * 0.1)
    assert nothing.holding(4.9) and not nothing.holding(AUTO_TOPIC_MAX_S)
