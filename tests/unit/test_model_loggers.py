"""Logger names, the loggers offered per node, and temporary levels: no ROS."""

import pytest

from console_tui.model.loggers.logger_levels import (
    GraphNode,
    LoggerSource,
    NodeLoggers,
    TemporaryLevels,
    ancestors,
    effective_level,
    format_remaining,
    level_text,
    match_nodes,
    node_logger_name,
    node_of_logger,
    owner_of,
    split_fqn,
)

from support.memory_control import StepClock


@pytest.mark.parametrize(
    ("namespace", "name", "logger"),
    [("/", "talker", "talker"), ("/ns", "talker", "ns.talker"), ("/a/b/", "n", "a.b.n"), ("", "n", "n")],
)
def test_node_logger_name(namespace, name, logger):
    assert node_logger_name(namespace, name) == logger
    assert GraphNode(namespace or "/", name).logger_name == logger


def test_fqn_round_trip():
    assert split_fqn("/ns/talker") == ("/ns", "talker")
    assert split_fqn("/talker") == ("/", "talker")
    assert GraphNode("/", "talker").fqn == "/talker"
    assert GraphNode("/ns", "talker").fqn == "/ns/talker"


def test_ancestors_end_with_the_default():
    assert ancestors("a.b.c") == ["a.b", "a", ""]
    assert ancestors("a") == [""]
    assert ancestors("") == []


def test_owner_is_the_longest_dotted_prefix():
    nodes = {"a", "a.b", "x"}
    assert owner_of("a.b.c", nodes) == "a.b"
    assert owner_of("a.b", nodes) == "a.b"
    assert owner_of("a.bc", nodes) == "a"
    assert owner_of("a.c.d", nodes) == "a"
    assert owner_of("xy", nodes) is None
    assert owner_of("", nodes) is None


def test_node_of_a_records_logger():
    nodes = [GraphNode("/", "a"), GraphNode("/a", "b"), GraphNode("/", "x")]
    assert node_of_logger("a.b.child", nodes).fqn == "/a/b"
    assert node_of_logger("a.other", nodes).fqn == "/a"
    assert node_of_logger("rcl", nodes) is None


def test_effective_level_walks_up_to_the_default():
    levels = {"": 20, "a": 0, "a.b": 10, "a.b.c": 0}
    assert effective_level("a.b.c", levels) == 10
    assert effective_level("a", levels) == 20
    assert effective_level("z.y", levels) == 20
    assert effective_level("a", {}) is None


def test_level_text():
    assert level_text(10) == "DEBUG"
    assert level_text(0) == "inherited"
    assert level_text(None) == "?"
    assert level_text(15) == "15"


def test_format_remaining():
    assert format_remaining(9.2) == "10s"
    assert format_remaining(0.1) == "1s"
    assert format_remaining(0) == "0s"
    assert format_remaining(-3) == "0s"
    assert format_remaining(65) == "1:05"


def test_match_nodes_forms():
    nodes = [GraphNode("/", "talker"), GraphNode("/ns", "talker"), GraphNode("/ns", "listener")]
    assert [n.fqn for n in match_nodes("/ns/talker", nodes)] == ["/ns/talker"]
    assert [n.fqn for n in match_nodes("ns/talker", nodes)] == ["/ns/talker"]
    assert [n.fqn for n in match_nodes("talker", nodes)] == ["/talker"]
    assert [n.fqn for n in match_nodes("listener", nodes)] == ["/ns/listener"]
    assert [n.fqn for n in match_nodes("ns.listener", nodes)] == ["/ns/listener"]
    assert match_nodes("nobody", nodes) == []
    two = [GraphNode("/a", "n"), GraphNode("/b", "n")]
    assert len(match_nodes("n", two)) == 2


def test_node_loggers_offer_own_children_typed_default():
    node = GraphNode("/ns", "talker", True)
    loggers = NodeLoggers(node)
    all_nodes = {"ns.talker", "ns.talker.inner", "other"}
    seen = [
        "ns.talker",
        "ns.talker.sub",
        "ns.talker.sub.deep",
        "ns.talker.inner",
        "ns.talker.inner.x",
        "other",
        "ns.talkerx",
    ]
    assert loggers.note_seen(seen, all_nodes)
    assert not loggers.note_seen(seen, all_nodes)
    loggers.add_typed("  my.lib ")
    loggers.add_typed("ns.talker.sub")  # already offered: not twice
    assert loggers.names() == ["ns.talker", "ns.talker.sub", "ns.talker.sub.deep", "my.lib", ""]
    sources = [loggers.source_of(n) for n in loggers.names()]
    assert sources == [
        LoggerSource.OWN,
        LoggerSource.CHILD,
        LoggerSource.CHILD,
        LoggerSource.TYPED,
        LoggerSource.DEFAULT,
    ]
    assert loggers.names_to_read() == ["ns.talker", "ns", "", "ns.talker.sub", "ns.talker.sub.deep", "my.lib", "my"]


def test_rows_show_inherited_levels_and_temporaries():
    node = GraphNode("/ns", "talker", True)
    loggers = NodeLoggers(node)
    loggers.note_seen(["ns.talker.sub"], {"ns.talker"})
    rows = loggers.rows()
    assert [r.level_text for r in rows] == ["?", "?", "?"]
    loggers.update_levels({"": 20, "ns": 0, "ns.talker": 10, "ns.talker.sub": 0})
    clock = StepClock(100.0)
    temporaries = TemporaryLevels(clock)
    temporaries.start("/ns/talker", "ns.talker", 10, 0, 30)
    temporaries.start("/other", "ns.talker", 10, 0, 30)
    rows = loggers.rows(temporaries.pending())
    assert [(r.name, r.level_text) for r in rows] == [
        ("ns.talker", "DEBUG"),
        ("ns.talker.sub", "inherited (DEBUG)"),
        ("", "INFO"),
    ]
    assert rows[0].temporary is not None and rows[0].temporary.node == "/ns/talker"
    assert rows[1].temporary is None


def test_temporary_levels_come_due_in_order():
    clock = StepClock(100.0)
    temporaries = TemporaryLevels(clock)
    first = temporaries.start("/a", "a", 10, 20, 5)
    temporaries.start("/b", "b", 10, 0, 2)
    assert first.remaining(clock.now) == 5
    assert temporaries.next_deadline() == 102
    clock.now = 101
    assert temporaries.take_due() == []
    clock.now = 105
    due = temporaries.take_due()
    assert [(e.node, e.previous) for e in due] == [("/b", 0), ("/a", 20)]
    assert len(temporaries) == 0 and temporaries.next_deadline() is None


def test_temporary_again_keeps_the_original_previous_level():
    clock = StepClock(100.0)
    temporaries = TemporaryLevels(clock)
    temporaries.start("/a", "a", 10, 30, 5)
    again = temporaries.start("/a", "a", 20, 10, 60)
    assert again.previous == 30 and again.level == 20 and again.deadline == 160


def test_cancel_retry_and_take_all():
    clock = StepClock(100.0)
    temporaries = TemporaryLevels(clock)
    entry = temporaries.start("/a", "a", 10, 30, 5)
    assert temporaries.cancel("/a", "a") == entry
    assert temporaries.cancel("/a", "a") is None
    retried = temporaries.retry_later(entry, 1.0)
    assert retried.attempts == 1 and retried.deadline == 101
    # A temporary level started meanwhile is not replaced by the retry.
    newer = temporaries.start("/a", "a", 40, 20, 9)
    assert temporaries.retry_later(entry, 1.0).deadline == 101
    assert temporaries.get("/a", "a").level == 40 and temporaries.get("/a", "a").previous == newer.previous
    temporaries.start("/b", "b", 10, 0, 3)
    assert {e.node for e in temporaries.take_all()} == {"/a", "/b"}
    assert temporaries.pending() == ()


def test_an_empty_graph_is_looked_for_then_has_no_nodes_yet_and_files_have_no_ros():
    from console_tui.model.loggers.logger_pane_state import LOOKING_TEXT, NO_ROS_TEXT, LoggerPaneState

    view = LoggerPaneState()
    assert view.notice_text(looking=True) == (LOOKING_TEXT, False)
    assert view.notice_text() == ("No nodes in the ROS graph yet.", False)
    assert view.notice_text("the master is gone", looking=True) == ("the master is gone", True)
    assert LoggerPaneState(has_ros=False).notice_text(looking=True) == (NO_ROS_TEXT, False)
