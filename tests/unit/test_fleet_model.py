"""A fleet's records in the model, without ROS: ``robot:`` in the query line and rules files,
nodes counted per robot, storms that never join two robots, the status line's robots."""

from __future__ import annotations

import pytest

from console_tui.model.overview.node_stats import NodeStats, robot_counts
from console_tui.model.rules.query import QueryError, parse_query
from console_tui.model.rules.robot import RobotRule
from console_tui.model.rules.ruleset import RuleSet
from console_tui.model.rules.rulesfile import load_rules, save_rules
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView
from console_tui.sources.status import SourceStatus
from console_tui.ui.widgets.status_bar import StatusFacts, empty_hint, render_status


def fleet_store(*robots: str, per_robot: int = 3) -> LogStore:
    store = LogStore()
    store.extend_records([LogRecord(1_000, 20, "/talker", "m")])  # before the fleet: no robot
    for robot in robots:
        store.extend_records(
            [LogRecord(2_000 + i, 20 + 10 * (i % 2), "/talker", f"{robot} {i}", robot=robot) for i in range(per_robot)]
        )
    return store


def shown(store: LogStore, query: str) -> list[tuple[str, str]]:
    view = LogView(store)
    view.set_rules(RuleSet().with_query(parse_query(query)))
    while not view.refilter_step(1.0):
        pass
    return [(store.get(view.seq_at(row)).robot, store.get(view.seq_at(row)).msg) for row in range(len(view))]


def test_robot_in_the_query_line_matches_names_and_globs_and_never_the_robotless():
    store = fleet_store("picker", "cart", "arm2")
    assert {robot for robot, _ in shown(store, "robot:picker")} == {"picker"}
    assert {robot for robot, _ in shown(store, "robot:picker,arm*")} == {"picker", "arm2"}
    assert {robot for robot, _ in shown(store, "-robot:cart")} == {"", "picker", "arm2"}
    assert shown(store, "robot:picker level>=warn") == [("picker", "picker 1")]
    assert shown(LogStore(), "robot:x") == []
    with pytest.raises(QueryError, match="needs a value"):
        parse_query("robot:")


def test_a_node_of_one_robot_matches_that_robots_records_only():
    store = fleet_store("picker", "cart", "arm2")
    assert {robot for robot, _ in shown(store, "node:picker:/talker")} == {"picker"}
    assert {robot for robot, _ in shown(store, "node:picker:/talker,arm*:/talker")} == {"picker", "arm2"}
    assert {robot for robot, _ in shown(store, "node:/talker")} == {"", "picker", "cart", "arm2"}
    assert {robot for robot, _ in shown(store, "node:/talker,cart:/nobody")} == {"", "picker", "cart", "arm2"}
    assert {robot for robot, _ in shown(store, "-node:cart:/talker")} == {"", "picker", "arm2"}
    assert shown(fleet_store(), "node:picker:/talker") == []  # no robot at all


def test_a_robot_rule_goes_through_a_rules_file(tmp_path):
    rules = RuleSet().with_query(parse_query("robot:picker,arm*"))
    save_rules(rules, tmp_path / "rules.toml")
    loaded = load_rules(tmp_path / "rules.toml")
    assert loaded.entries[0].rule == RobotRule(("picker", "arm*"))
    assert 'kind = "robot"' in (tmp_path / "rules.toml").read_text()
    assert RobotRule(("picker",)).describe() == "robot picker"


def test_the_same_node_on_two_robots_is_two_nodes():
    store = fleet_store("picker", "cart")
    stats = NodeStats(store)
    stats.update()
    rows = {(entry.robot, entry.node): entry for entry in stats.nodes()}
    assert set(rows) == {("", "/talker"), ("picker", "/talker"), ("cart", "/talker")}
    assert rows[("picker", "/talker")].counts == (0, 2, 1, 0, 0)
    assert rows[("cart", "/talker")].label == "cart: /talker"
    assert rows[("", "/talker")].label == "/talker"
    assert robot_counts(stats.nodes()) == {"": (0, 1, 0, 0, 0), "cart": (0, 2, 1, 0, 0), "picker": (0, 2, 1, 0, 0)}


def test_counts_per_robot_follow_the_store_dropping_the_oldest():
    store = LogStore(max_messages=4)
    stats = NodeStats(store)
    store.extend_records([LogRecord(i, 20, "/n", "x", robot="a") for i in range(3)])
    stats.update()
    store.extend_records([LogRecord(10 + i, 20, "/n", "x", robot="b") for i in range(3)])
    stats.update()
    assert {entry.robot: entry.total for entry in stats.nodes()} == {"a": 1, "b": 3}


def test_a_message_repeated_by_two_robots_is_no_storm():
    from console_tui.model.overview.storms import StormRows

    store = LogStore()
    store.extend_records([LogRecord(i, 20, "/talker", "same", robot="ab"[i % 2]) for i in range(6)])
    store.extend_records([LogRecord(10 + i, 20, "/talker", "again", robot="a") for i in range(3)])
    rows = StormRows(store, LogView(store))
    assert rows.sync()
    assert len(rows) == 7  # the six alternating rows, and one storm of three


def test_the_status_line_says_each_robots_state_in_a_mark():
    robots = [
        SourceStatus(topic="/rosout", publishers=2, running=True, robot="picker"),
        SourceStatus(topic="/rosout", running=True, robot="cart", lost=5, lost_queue=3),
        SourceStatus(problem="the intake process ended", robot="arm", lost=3, lost_queue=3),
    ]
    text = render_status(StatusFacts(total=3, sources=robots)).plain
    assert "picker✓ cart… arm✗" in text
    assert "5 lost" in text  # the app's drops (in every robot's count) once
    assert "/rosout" not in text  # the summary says the rest
    one = render_status(StatusFacts(sources=[robots[0]])).plain
    assert "/rosout 2 pubs" in one and "picker✓" not in one


def test_an_empty_table_says_each_robots_state():
    robots = [
        SourceStatus(topic="/rosout", publishers=1, running=True, robot="picker"),
        SourceStatus(path="starting", robot="cart"),
        SourceStatus(problem="master gone", robot="arm"),
    ]
    assert empty_hint(StatusFacts(sources=robots)) == (
        "waiting for the robots' messages: picker receiving, cart starting, arm problem…"
    )
