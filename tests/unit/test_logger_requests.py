"""The logger pane's calls and their books (``LoggerRequests``) without a screen: over an
in-memory graph (``MemoryControl``), the ends of calls handed back through a queue as the
pane's messages hand them back to its thread."""

from __future__ import annotations

import queue

import pytest

from console_tui.control.events import NodesChanged, TemporaryEnded
from console_tui.model.loggers.logger_pane_state import NO_ROS_TEXT
from console_tui.ui.widgets.logger_requests import CallEnded, LoggerRequests

from support.memory_control import MemoryControl, MemoryNode

ALPHA = "/ns/alpha"


@pytest.fixture
def control():
    control = MemoryControl([MemoryNode(ALPHA), MemoryNode("/beta", services=False)], call_timeout=0.5)
    control.start()
    control.wait_for_graph(0.1)
    yield control
    control.close()


class Desk:
    """Requests whose deliveries wait in a queue, taken on the test's thread as the pane would."""

    def __init__(self, control: MemoryControl | None) -> None:
        self.delivered: queue.Queue = queue.Queue()
        self.requests = LoggerRequests(control, self.delivered.put, seen_loggers=["ns.alpha", "ns.alpha.child"])
        self.state = self.requests.state

    def finish_next(self) -> str | None:
        while True:
            item = self.delivered.get(timeout=5)
            if isinstance(item, (CallEnded, TemporaryEnded)):
                return self.requests.finish(item)


def test_selecting_a_node_reads_its_loggers_seen_in_records(control):
    desk = Desk(control)
    desk.requests.set_nodes(control.nodes)
    assert desk.requests.select(ALPHA) is True
    assert desk.state.pending == {ALPHA: 1} and desk.state.heading() == f"Loggers of {ALPHA} …"
    assert desk.finish_next() is None
    assert desk.state.pending == {ALPHA: 0}
    assert {row.name: row.level for row in desk.state.rows()} == {"": 20, "ns.alpha": 0, "ns.alpha.child": 0}


def test_setting_a_level_says_so_and_reads_the_levels_again(control):
    desk = Desk(control)
    desk.requests.set_nodes(control.nodes)
    desk.requests.select(ALPHA)
    desk.finish_next()
    desk.requests.set_level(ALPHA, "ns.alpha", 10)
    assert desk.finish_next() is None
    assert desk.state.notice == "ns.alpha set to DEBUG" and desk.state.pending == {ALPHA: 1}  # the read again
    assert desk.finish_next() is None
    assert next(row.level for row in desk.state.rows() if row.name == "ns.alpha") == 10


def test_a_refused_level_is_the_failure_to_report(control):
    desk = Desk(control)
    desk.requests.set_nodes(control.nodes)
    desk.requests.set_level(ALPHA, "ns.alpha", 15)  # MemoryControl refuses levels between steps
    failure = desk.finish_next()
    assert failure is not None and failure.startswith("Could not set ns.alpha to ") and "odd level" in failure


def test_a_temporary_level_ends_and_its_level_comes_back(control):
    desk = Desk(control)
    desk.requests.listen()
    desk.requests.set_nodes(control.nodes)
    desk.requests.set_temporary(ALPHA, "ns.alpha", 10, 0.2)
    assert desk.finish_next() is None
    assert "for 0.2 s, then back to inherited" in desk.state.notice
    assert [t.logger for t in desk.state.temporaries] == ["ns.alpha"]
    while True:
        item = desk.delivered.get(timeout=5)
        if isinstance(item, TemporaryEnded):
            break
    assert desk.requests.finish(item) is None
    assert desk.state.notice == f"ns.alpha of {ALPHA} is back to inherited" and desk.state.temporaries == ()


def test_nodes_changed_are_delivered_once_listening(control):
    desk = Desk(control)
    desk.requests.listen()
    control.graph["/gamma"] = MemoryNode("/gamma")
    item = desk.delivered.get(timeout=5)
    assert isinstance(item, NodesChanged) and "/gamma" in {node.fqn for node in item.nodes}


def test_without_a_control_nothing_is_called_and_the_view_says_why():
    desk = Desk(None)
    desk.requests.set_level("/a", "a", 10)
    assert desk.state.notice == NO_ROS_TEXT and desk.state.notice_is_error
    assert desk.delivered.empty() and not desk.requests.take_temporaries() and desk.requests.problem == ""
