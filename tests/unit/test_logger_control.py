"""The ROS-neutral part of the logger control, over an in-memory graph of nodes (no ROS).

``MemoryControl`` is the smallest subclass the base accepts: it shows what a ROS provides.
The ROS 2 control is tested against real nodes in tests/ros/test_ros2_logger_control.py.
"""

from __future__ import annotations

import threading

import pytest

from console_tui.control.errors import CallTimedOut, ControlClosed, LevelRefused, NodeNotFound, NoLoggerServices
from console_tui.control.events import NodesChanged, TemporaryEnded

from support.memory_control import MemoryControl, MemoryNode, StepClock, running
from support.rosproc import wait_until


@pytest.fixture
def control():
    nodes = [MemoryNode("/ns/alpha"), MemoryNode("/beta", services=False), MemoryNode("/_hidden")]
    yield from running(MemoryControl(nodes, call_timeout=0.5))


def test_the_graph_leaves_out_hidden_nodes_and_says_who_has_services(control):
    assert [(n.fqn, n.has_logger_services) for n in control.wait_for_graph(0.1).nodes] == [
        ("/beta", False),
        ("/ns/alpha", True),
    ]
    assert any(isinstance(event, NodesChanged) for event in control.events)
    assert control.is_settled("/ns/alpha") and control.node("/nobody") is None


def test_waiting_for_the_graph_lasts_until_no_node_came_for_the_quiet_time():
    # As Fast DDS discovery goes under load: nodes seen at once, one more seconds later.
    clock = StepClock()
    control = MemoryControl([MemoryNode("/a")], clock=clock)
    control.graph_min_s, control.graph_quiet_s = 5.0, 2.0
    control.start()
    try:
        assert wait_until(lambda: control.nodes)
        seen = []
        waiter = threading.Thread(target=lambda: seen.append(control.wait_for_graph(10.0)))
        waiter.start()

        def at(when: float, arriving: str | None = None) -> None:
            clock.now = when
            if arriving:
                control.graph[arriving] = MemoryNode(arriving)
                assert wait_until(lambda: control.node(arriving) is not None)
            else:
                looks = control._graph.refreshes
                assert wait_until(lambda: control._graph.refreshes > looks)

        at(1.0, "/b")
        at(3.5)  # quiet for 2.5 s, but not watched for 5 s yet
        at(4.6, "/c")
        at(6.5)
        waiter.join(0.3)
        assert waiter.is_alive() and not seen  # /c came 1.9 s ago
        clock.now = 6.6
        waiter.join(5)
        assert [node.fqn for node in seen[0].nodes] == ["/a", "/b", "/c"]
        assert seen[0].settled and seen[0].waited_s == pytest.approx(6.6)
    finally:
        control.close()


def test_a_graph_that_came_at_once_is_watched_for_the_minimum_time():
    clock = StepClock()
    control = MemoryControl([MemoryNode("/a"), MemoryNode("/b")], clock=clock)
    control.graph_min_s, control.graph_quiet_s = 5.0, 2.0
    control.start()
    try:
        seen = []
        waiter = threading.Thread(target=lambda: seen.append(control.wait_for_graph(10.0)))
        waiter.start()
        assert wait_until(lambda: len(control.nodes) == 2)
        clock.now = 4.9
        waiter.join(0.3)
        assert waiter.is_alive()
        clock.now = 5.0
        waiter.join(5)
        assert len(seen[0].nodes) == 2 and seen[0].settled and seen[0].waited_s == pytest.approx(5.0)
    finally:
        control.close()


def test_looking_lasts_from_the_start_until_the_graph_was_watched_and_quiet():
    """What the pane says while it has no node: looking, then (an empty graph) none yet."""
    clock = StepClock()
    control = MemoryControl([], clock=clock)
    control.graph_min_s, control.graph_quiet_s = 5.0, 2.0
    assert not control.looking(), "not started: nothing is looked for"
    control.start()
    try:
        assert control.looking()
        assert wait_until(lambda: control._graph.refreshes > 0)
        clock.now = 4.9
        assert control.looking(), "watched for less than the minimum"
        control.graph["/late"] = MemoryNode("/late")  # a node discovery found late
        assert wait_until(lambda: control.node("/late") is not None)
        clock.now = 5.5
        assert control.looking(), "a node came 0.6 s ago"
        clock.now = 7.0
        assert not control.looking()
    finally:
        control.close()
    assert not control.looking()


def test_waiting_for_an_empty_graph_ends_at_the_deadline_unsettled():
    clock = StepClock()
    control = MemoryControl([], clock=clock)
    control.start()
    try:
        seen = []
        waiter = threading.Thread(target=lambda: seen.append(control.wait_for_graph(4.0)))
        waiter.start()
        assert wait_until(lambda: control._graph.refreshes > 0)
        clock.now = 3.9
        waiter.join(0.3)
        assert waiter.is_alive()
        clock.now = 4.0
        waiter.join(5)
        assert seen[0].nodes == () and not seen[0].settled and seen[0].waited_s == pytest.approx(4.0)
    finally:
        control.close()


def test_get_set_and_the_failures_each_with_its_own_error(control):
    assert control.get_levels("/ns/alpha", ["ns.alpha", ""]).result(timeout=5) == {"ns.alpha": 0, "": 20}
    assert control.set_level("/ns/alpha", "ns.alpha", 10).result(timeout=5) == {"ns.alpha": 10}
    assert control.get_levels("/ns/alpha", ["ns.alpha"]).result(timeout=5) == {"ns.alpha": 10}
    with pytest.raises(LevelRefused, match="odd level"):
        control.set_level("/ns/alpha", "ns.alpha", 15).result(timeout=5)
    with pytest.raises(LevelRefused, match="cannot be unset"):
        control.set_level("/ns/alpha", "", 0).result(timeout=5)
    with pytest.raises(LevelRefused, match="not a level"):
        control.set_level("/ns/alpha", "ns.alpha", -1).result(timeout=5)
    with pytest.raises(NodeNotFound):
        control.get_levels("/nobody", ["x"]).result(timeout=5)
    with pytest.raises(NoLoggerServices, match="give it some"):
        control.get_levels("/beta", ["beta"]).result(timeout=5)


def test_a_busy_node_times_out_and_its_call_is_dropped(control):
    control.graph["/ns/alpha"].busy = threading.Event()
    with pytest.raises(CallTimedOut, match=r"did not answer within 0\.5 s"):
        control.get_levels("/ns/alpha", ["ns.alpha"]).result(timeout=5)
    assert control.dropped == ["/ns/alpha"]


def test_temporary_levels_end_on_time_and_keep_the_first_previous_level(control):
    alpha = control.graph["/ns/alpha"]
    control.set_level("/ns/alpha", "ns.alpha", 30).result(timeout=5)
    control.set_temporary("/ns/alpha", "ns.alpha", 10, 60).result(timeout=5)
    entry = control.set_temporary("/ns/alpha", "ns.alpha", 40, 0.2).result(timeout=5)
    assert (entry.level, entry.previous) == (40, 30) and alpha.levels["ns.alpha"] == 40
    assert wait_until(lambda: any(isinstance(e, TemporaryEnded) for e in control.events))
    ended = next(e for e in control.events if isinstance(e, TemporaryEnded))
    assert ended.entry == entry and ended.error is None
    assert alpha.levels["ns.alpha"] == 30 and control.temporaries() == ()


def test_close_puts_temporary_levels_back_and_refuses_later_calls(control):
    alpha = control.graph["/ns/alpha"]
    control.set_temporary("/ns/alpha", "ns.alpha", 10, 60).result(timeout=5)
    control.close()
    assert alpha.levels["ns.alpha"] == 0 and control.shut
    with pytest.raises(ControlClosed):
        control.get_levels("/ns/alpha", ["ns.alpha"]).result(timeout=5)
