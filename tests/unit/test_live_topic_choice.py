"""How the live source picks /rosout_agg over /rosout without showing a message twice."""

from __future__ import annotations

from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.sources.ros2.topic_choice import DISCOVERY_S, SWITCH_DEDUPE_S, TopicChoice


def records(node: str, *stamps: int) -> list[LogRecord]:
    return [LogRecord(stamp, 20, node, f"{node} {stamp}", source="") for stamp in stamps]


def taken(records: list[LogRecord]) -> RecordColumns:
    """A batch as the topic reader takes it."""
    return RecordColumns.from_records(records)


def passed(choice: TopicChoice, records: list[LogRecord], topic: str, now: float) -> list[LogRecord]:
    """What the choice lets on of ``records``, as records."""
    return choice.filter(taken(records), topic, now).records()


def test_rosout_goes_on_at_once_without_an_aggregator():
    choice = TopicChoice(0.0)
    assert [r.stamp_ns for r in passed(choice, records("a", 1, 2), "/rosout", 0.1)] == [1, 2]
    assert [r.stamp_ns for r in passed(choice, records("a", 3), "/rosout", 9.0)] == [3]


def test_aggregator_found_at_once_gives_all_of_its_history():
    choice = TopicChoice(0.0)
    choice.switched(0.1)
    history = records("a", 1, 2, 3, 4, 5, 6)
    assert passed(choice, history, "/rosout_agg", 0.2) == history


def test_aggregator_found_after_the_first_rows_gives_only_what_was_not_shown():
    choice = TopicChoice(0.0)
    assert len(passed(choice, records("a", 5, 6), "/rosout", 0.5)) == 2
    choice.switched(1.0)
    history = records("a", 1, 2, 3, 4, 5, 6, 7)
    assert [r.stamp_ns for r in passed(choice, history, "/rosout_agg", 1.1)] == [1, 2, 3, 4, 7]


def test_aggregator_found_later_gives_only_what_was_not_seen():
    choice = TopicChoice(0.0)
    assert [r.stamp_ns for r in passed(choice, records("a", 1), "/rosout", 0.1)] == [1]
    assert [r.stamp_ns for r in passed(choice, records("a", 2) + records("b", 7), "/rosout", 5.0)] == [2, 7]
    choice.switched(10.0)
    history = records("a", 1, 2, 3) + records("b", 6, 7, 8) + records("c", 1)
    got = passed(choice, history, "/rosout_agg", 10.1)
    # b 6 is older than anything /rosout gave for b (it keeps only its last 10 s): kept too.
    assert [(r.node, r.stamp_ns) for r in got] == [("a", 3), ("b", 6), ("b", 8), ("c", 1)]
    later = records("a", 1)  # long after the switch, nothing is held against anything
    assert passed(choice, later, "/rosout_agg", 10.0 + SWITCH_DEDUPE_S + 1) == later


def test_discovery_is_watched_closely_for_the_first_seconds_only():
    choice = TopicChoice(10.0)
    assert choice.discovering(10.0) and choice.discovering(10.0 + DISCOVERY_S - 0.01)
    assert not choice.discovering(10.0 + DISCOVERY_S)
