"""Logger levels across a fleet, over in-memory graphs (no ROS): every robot's nodes listed as
``ROBOT:/node``, each call sent to its robot only, events renamed, a robot's problem its own."""

from __future__ import annotations

import pytest

from console_tui.control.errors import LoggerCallError
from console_tui.control.events import NodesChanged, TemporaryEnded
from console_tui.control.fleet_control import FleetLoggerControl, split_node
from console_tui.model.loggers.logger_levels import GraphNode, node_of_logger

from support.memory_control import MemoryControl, MemoryNode, running
from support.rosproc import wait_until


@pytest.fixture
def fleet():
    controls = {
        "picker": MemoryControl([MemoryNode("/talker"), MemoryNode("/arm")], call_timeout=0.5),
        "cart": MemoryControl([MemoryNode("/talker")], call_timeout=0.5),
    }
    yield from running(FleetLoggerControl(controls))


def test_every_robots_nodes_named_for_their_robot(fleet):
    assert wait_until(lambda: len(fleet.nodes) == 3, timeout=10)
    assert [node.fqn for node in fleet.nodes] == ["cart:/talker", "picker:/arm", "picker:/talker"]
    assert fleet.node("cart:/talker") == GraphNode("/", "talker", True, "cart")
    assert fleet.node("/talker") is None
    assert wait_until(lambda: fleet.is_settled("picker:/talker"), timeout=10)
    assert any(isinstance(event, NodesChanged) and len(event.nodes) == 3 for event in fleet.events)
    assert [node.fqn for node in fleet.find_node("cart:talker", 1)] == ["cart:/talker"]
    assert sorted(node.fqn for node in fleet.find_node("talker", 1)) == ["cart:/talker", "picker:/talker"]
    waited = fleet.wait_for_graph(5)
    assert len(waited.nodes) == 3


def test_a_level_set_on_one_robots_node_never_reaches_the_same_name_on_another(fleet):
    assert wait_until(lambda: len(fleet.nodes) == 3, timeout=10)
    assert fleet.set_level("picker:/talker", "talker", 10).result(timeout=5) == {"talker": 10}
    assert fleet.controls["picker"].graph["/talker"].levels["talker"] == 10
    assert "talker" not in fleet.controls["cart"].graph["/talker"].levels
    assert fleet.get_levels("cart:/talker", ["talker"]).result(timeout=5) == {"talker": 0}
    with pytest.raises(LoggerCallError, match="name the robot first, as ROBOT:/node"):
        fleet.get_levels("/talker", ["talker"]).result(timeout=5)


def test_temporary_levels_and_their_end_are_named_for_the_robot(fleet):
    assert wait_until(lambda: len(fleet.nodes) == 3, timeout=10)
    entry = fleet.set_temporary("cart:/talker", "talker", 10, 0.2).result(timeout=5)
    assert entry.node == "cart:/talker"
    assert wait_until(lambda: any(isinstance(e, TemporaryEnded) for e in fleet.events), timeout=10)
    ended = next(e for e in fleet.events if isinstance(e, TemporaryEnded))
    assert ended.entry.node == "cart:/talker" and ended.error is None
    assert fleet.temporaries() == ()


def test_a_robots_problem_names_it_and_split_node_knows_the_robots():
    assert split_node("picker:/talker", ["picker"]) == ("picker", "/talker")
    assert split_node("other:/talker", ["picker"]) == ("", "other:/talker")
    controls = {"picker": MemoryControl([]), "cart": MemoryControl([])}
    fleet = FleetLoggerControl(controls)
    controls["cart"].problem = "master gone"
    assert fleet.problem == "cart: master gone"


def test_a_rows_node_is_found_on_the_rows_robot():
    nodes = [GraphNode("/", "talker", True, "a"), GraphNode("/", "talker", True, "b")]
    assert node_of_logger("talker", nodes, "b") == nodes[1]
    assert node_of_logger("/talker", nodes, "a") == nodes[0]
    assert node_of_logger("talker", nodes, "c") is None


def test_a_fleet_is_looking_while_any_robots_graph_is():
    from support.memory_control import StepClock

    clock = StepClock()
    quick = MemoryControl([MemoryNode("/a")], clock=clock)
    slow = MemoryControl([], clock=clock)
    for control in (quick, slow):
        control.graph_min_s, control.graph_quiet_s = 1.0, 1.0
    slow.graph_min_s = 5.0
    fleet = FleetLoggerControl({"quick": quick, "slow": slow})
    assert not fleet.looking()
    fleet.start()
    try:
        assert wait_until(lambda: quick._graph.refreshes and slow._graph.refreshes)
        clock.now = 2.0
        assert not quick.looking() and fleet.looking()
        clock.now = 5.0
        assert not fleet.looking()
    finally:
        fleet.close()
