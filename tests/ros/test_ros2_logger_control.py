"""Logger levels against real rclpy node processes: the graph, get/set, temporary levels, failures."""

from __future__ import annotations

import time

import pytest

from support.memory_control import running
from support.rosproc import wait_until

pytestmark = pytest.mark.ros2

ALPHA = "/ns/alpha"


@pytest.fixture
def control(ros_runtime):
    from console_tui.control.ros2.logger_control import Ros2LoggerControl

    yield from running(Ros2LoggerControl(ros_runtime, call_timeout=1.5))


class Rosout:
    """Records read from /rosout by the project's live source."""

    def __init__(self, runtime) -> None:
        from console_tui.model.store.intake_queue import IntakeQueue
        from console_tui.sources.ros2.live_source import LiveLogSource

        self.queue = IntakeQueue()
        self.source = LiveLogSource(runtime, self.queue, topic="/rosout")
        self.records = []
        self.source.start()

    def messages(self) -> set[str]:
        self.records.extend(self.queue.drain())
        return {record.msg for record in self.records}

    def wait_for(self, msg: str) -> set[str]:
        assert wait_until(lambda: msg in self.messages()), f"{msg!r} never arrived"
        return self.messages()


@pytest.fixture
def rosout(ros_runtime):
    reader = Rosout(ros_runtime)
    yield reader
    reader.source.stop()


def start_alpha(nodes, *others):
    """Start /ns/alpha and the talkers named in ``others`` (argument lists) together."""
    alpha = nodes.start("talker.py", "--name", "alpha", "--namespace", "/ns")
    started = [nodes.start("talker.py", *args) for args in others]
    for process in [alpha, *started]:
        process.expect("ready")
    return alpha


def ready(control, fqn=ALPHA):
    found = control.find_node(fqn, wait=15)
    assert found and found[0].has_logger_services, f"{fqn} not discovered with its logger services"
    return found[0]


def log_all(process, tag, **extra):
    process.send({"cmd": "log_all", "tag": tag, **extra})
    process.expect("logged")
    process.lines.clear()


def test_graph_lists_nodes_and_marks_the_one_without_services(nodes, control):
    from console_tui.control.errors import NoLoggerServices
    from console_tui.control.events import NodesChanged

    start_alpha(nodes, ["--name", "beta", "--no-logger-service"])
    ready(control)
    beta = control.find_node("/beta", wait=15)
    assert [(n.fqn, n.has_logger_services) for n in beta] == [("/beta", False)]
    assert control.is_settled("/beta") and control.is_settled(ALPHA) and not control.is_settled("/nobody")
    listed = {n.fqn: n for n in control.nodes}
    assert set(listed) == {ALPHA, "/beta"}, "console-tui's own nodes are never listed"
    assert listed[ALPHA].logger_name == "ns.alpha"
    assert wait_until(  # the graph watcher posts the change on its own time
        lambda: any(isinstance(e, NodesChanged) and ALPHA in {n.fqn for n in e.nodes} for e in list(control.events))
    )
    with pytest.raises(NoLoggerServices, match="enable_logger_service=True"):
        control.get_levels("/beta", ["beta"]).result(timeout=10)


def test_get_and_set_round_trip_and_a_refused_level(nodes, control):
    from console_tui.control.errors import LevelRefused, NodeNotFound

    start_alpha(nodes)
    ready(control)
    assert control.get_levels(ALPHA, ["ns.alpha", ""]).result(timeout=10) == {"ns.alpha": 0, "": 20}
    control.set_level(ALPHA, "ns.alpha", 10).result(timeout=10)
    assert control.get_levels(ALPHA, ["ns.alpha"]).result(timeout=10) == {"ns.alpha": 10}
    control.set_levels(ALPHA, {"ns.alpha": 0, "ns.alpha.child": 40}).result(timeout=10)
    assert control.get_levels(ALPHA, ["ns.alpha", "ns.alpha.child"]).result(timeout=10) == {
        "ns.alpha": 0,
        "ns.alpha.child": 40,
    }
    with pytest.raises(LevelRefused, match="Invalid logger level") as refused:
        control.set_level(ALPHA, "ns.alpha", 15).result(timeout=10)
    assert list(refused.value.refused) == ["ns.alpha"]
    with pytest.raises(LevelRefused, match="cannot be unset"):
        control.set_level(ALPHA, "", 0).result(timeout=10)
    with pytest.raises(LevelRefused, match="not a level"):
        control.set_level(ALPHA, "ns.alpha", -1).result(timeout=10)
    with pytest.raises(NodeNotFound):
        control.get_levels("/nobody", ["x"]).result(timeout=10)


def test_debug_level_lets_debug_messages_through_and_info_stops_them(nodes, control, rosout):
    from console_tui.model.loggers.logger_levels import NodeLoggers

    alpha = start_alpha(nodes)
    node = ready(control)
    log_all(alpha, "before")
    assert "before debug message" not in rosout.wait_for("before info message")

    control.set_level(ALPHA, "ns.alpha", 10).result(timeout=10)
    log_all(alpha, "on")
    log_all(alpha, "child", child="sub")
    seen = rosout.wait_for("child info message")
    assert {"on debug message", "child debug message"} <= seen
    loggers = NodeLoggers(node)
    loggers.note_seen({r.node for r in rosout.records}, {node.logger_name})
    assert "ns.alpha.sub" in loggers.names()

    control.set_level(ALPHA, "ns.alpha", 20).result(timeout=10)
    log_all(alpha, "off")
    assert "off debug message" not in rosout.wait_for("off info message")


def test_temporary_debug_reverts_on_time(nodes, control, rosout):
    from console_tui.control.events import TemporaryEnded

    alpha = start_alpha(nodes)
    ready(control)
    entry = control.set_temporary(ALPHA, "ns.alpha", 10, 1.0).result(timeout=10)
    assert (entry.level, entry.previous) == (10, 0)
    assert control.temporaries() == (entry,)
    log_all(alpha, "during")
    assert "during debug message" in rosout.wait_for("during info message")

    assert wait_until(lambda: any(isinstance(e, TemporaryEnded) for e in control.events))
    ended = next(e for e in control.events if isinstance(e, TemporaryEnded))
    assert ended.entry == entry and ended.error is None
    assert control.temporaries() == ()
    assert control.get_levels(ALPHA, ["ns.alpha"]).result(timeout=10) == {"ns.alpha": 0}
    log_all(alpha, "after")
    assert "after debug message" not in rosout.wait_for("after info message")


def test_close_puts_temporary_levels_back(nodes, ros_runtime):
    from console_tui.control.ros2.logger_control import Ros2LoggerControl

    start_alpha(nodes)
    first = Ros2LoggerControl(ros_runtime)
    first.start()
    ready(first)
    first.set_level(ALPHA, "ns.alpha", 30).result(timeout=10)
    first.set_temporary(ALPHA, "ns.alpha", 10, 60).result(timeout=10)
    again = first.set_temporary(ALPHA, "ns.alpha", 40, 60).result(timeout=10)
    assert again.previous == 30, "a second temporary level keeps the level from before the first"
    first.close()
    with pytest.raises(Exception, match="closed"):
        first.get_levels(ALPHA, ["ns.alpha"]).result(timeout=10)

    second = Ros2LoggerControl(ros_runtime)
    second.start()
    try:
        ready(second)
        assert second.get_levels(ALPHA, ["ns.alpha"]).result(timeout=10) == {"ns.alpha": 30}
    finally:
        second.close()


def test_a_node_killed_during_a_call_gives_a_clear_failure(nodes, control):
    from console_tui.control.errors import CallTimedOut, NodeGone

    alpha = start_alpha(nodes, ["--name", "gamma"])
    ready(control)
    ready(control, "/gamma")
    alpha.send({"cmd": "block", "seconds": 30})
    alpha.expect("blocking")
    future = control.get_levels(ALPHA, ["ns.alpha"])
    time.sleep(0.2)
    alpha.kill()
    with pytest.raises((CallTimedOut, NodeGone)) as failure:
        future.result(timeout=10)
    assert ALPHA in str(failure.value)
    # The control carries on with the other nodes.
    assert control.get_levels("/gamma", ["gamma"]).result(timeout=10) == {"gamma": 0}


def test_a_node_that_exits_leaves_the_list(nodes, control):
    from console_tui.control.errors import NodeNotFound

    alpha = start_alpha(nodes)
    ready(control)
    alpha.stop()
    assert wait_until(lambda: control.node(ALPHA) is None)
    with pytest.raises(NodeNotFound, match="no such node"):
        control.set_level(ALPHA, "ns.alpha", 10).result(timeout=10)
