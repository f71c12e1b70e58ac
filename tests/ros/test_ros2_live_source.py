"""The live ROS 2 intake against real node processes: both decode paths, loss counts, stopping."""

from __future__ import annotations

import contextlib
import os
import struct
import time

import pytest
from nodes.stalled_intake import StalledQueue

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
from console_tui.ros.ros2.runtime import uses_fast_dds_2

from support.rosproc import PATIENCE_S, wait_until

pytestmark = pytest.mark.ros2


#: How messages are taken and decoded: the take loop in C, rclpy's take, rclpy's typed take.
PATHS = ["c+cdr", "raw+cdr", "typed"]


def take_by(path: str, monkeypatch) -> bool:
    """Make the next live source take messages by ``path``; whether that is a raw path."""
    from console_tui.sources.ros2 import compiled_take

    monkeypatch.setattr(compiled_take, "_loaded", None)
    monkeypatch.setattr(compiled_take, "_loading", None)
    if path == "raw+cdr":
        monkeypatch.setenv(compiled_take.SWITCH, "0")
    elif path == "c+cdr":
        function, problem = compiled_take.load()
        assert function is not None, f"the take loop in C did not build: {problem}"
    return path != "typed"


@contextlib.contextmanager
def live_source(topic: str = "/rosout", *, raw: bool = True, queue: IntakeQueue | None = None, min_level: int = 0):
    from console_tui.ros.ros2.runtime import RosRuntime
    from console_tui.sources.ros2.live_source import LiveLogSource

    runtime = RosRuntime()
    source = LiveLogSource(runtime, IntakeQueue() if queue is None else queue, topic, raw=raw, min_level=min_level)
    source.start()
    try:
        yield source
    finally:
        source.stop()
        runtime.shutdown()
    assert source._thread is not None and not source._thread.is_alive(), "the intake thread did not stop"


def collect(source, enough, timeout: float = PATIENCE_S) -> list[LogRecord]:
    records: list[LogRecord] = []

    def done() -> bool:
        records.extend(source.queue.drain())
        return enough(records)

    wait_until(done, timeout)
    return records


def log_until_one_arrives(talker, source, text: str) -> list[LogRecord]:
    """What arrives while ``talker`` logs ``TEXT N`` (WARN) again and again until one arrives:
    a VOLATILE publisher's messages reach only subscriptions already matched."""
    records: list[LogRecord] = []
    deadline = time.monotonic() + PATIENCE_S
    number = 0
    while not any(r.msg.startswith(text) for r in records) and time.monotonic() < deadline:
        talker.send({"cmd": "log", "level": "warn", "msg": f"{text} {number}"})
        talker.expect_next("logged")
        number += 1
        records += collect(source, lambda got: any(r.msg.startswith(text) for r in got), timeout=0.5)
    assert any(r.msg.startswith(text) for r in records), f"nothing of {text!r} arrived"
    return records


@pytest.mark.parametrize("path", PATHS)
def test_every_field_arrives_on_every_path(nodes, path, monkeypatch):
    raw = take_by(path, monkeypatch)
    talker = nodes.start("talker.py", "--name", "fields_talker", "--namespace", "/ns", "--debug")
    logger = talker.expect("ready")["logger"]
    with live_source(raw=raw) as source:
        assert wait_until(lambda: source.status.publishers >= 1)
        talker.send({"cmd": "log_all", "tag": "fields"})
        logged = talker.expect("logged")["messages"]
        records = collect(source, lambda got: sum(r.msg.startswith("fields ") for r in got) >= len(logged))
        status = source.status
    mine = [r for r in records if r.msg.startswith("fields ")]
    assert [(r.level, r.msg, r.file, r.function, r.line) for r in mine] == [
        (m["level"], m["msg"], m["file"], m["function"], m["line"]) for m in logged
    ]
    assert {r.node for r in mine} == {logger} and {r.source for r in mine} == {"/rosout"}
    assert all(r.stamp_ns > 0 for r in mine)
    assert status.path == path
    assert status.path_note == ("CONSOLE_TUI_COMPILED_TAKE=0" if path == "raw+cdr" else "")  # why not c+cdr
    assert (status.lost, status.decoded_by_rclpy, status.incompatible) == (0, 0, 0)


def serialized_log(msg: str, kind: int = 1) -> str:
    """A little-endian Log message with encapsulation ``kind``, as hex."""
    payload = struct.pack("<iIB", 5, 6, 20)
    for text in (b"raw.node", msg.encode(), b"f.py", b"fn"):
        payload += b"\x00" * (-len(payload) % 4) + struct.pack("<I", len(text) + 1) + text + b"\x00"
    payload += b"\x00" * (-len(payload) % 4) + struct.pack("<I", 3)
    return (bytes([0, kind, 0, 0]) + payload).hex()


@pytest.mark.parametrize("path", PATHS)
def test_unreadable_messages_are_counted_as_lost_and_others_still_arrive(nodes, path, monkeypatch):
    raw = take_by(path, monkeypatch)
    topic = "/raw_test_log"
    with live_source(topic, raw=raw) as source:
        publisher = nodes.start("raw_publisher.py", "--topic", topic)
        publisher.expect("ready")
        messages = [
            serialized_log("plain cdr"),
            serialized_log("parameter-list encapsulation", kind=3),  # rclpy reads it, the direct decoder does not
            "00010000ffffffff",  # truncated: nobody can read it
            "0001000005000000060000001400000000ffffff",  # a string length past the end
            serialized_log("after the bad ones"),
        ]
        publisher.send({"cmd": "publish", "hex": messages})
        publisher.expect("published")
        records = collect(source, lambda got: any(r.msg == "after the bad ones" for r in got))
        if raw:  # a typed take drops what it cannot deserialize inside the RMW, unseen
            assert wait_until(lambda: source.status.lost_undecodable >= 2)
        status = source.status
    assert [r.msg for r in records] == ["plain cdr", "parameter-list encapsulation", "after the bad ones"]
    assert records[0] == LogRecord(5_000_000_006, 20, "raw.node", "plain cdr", "f.py", "fn", 3, topic)
    assert (status.lost, status.lost_undecodable, status.lost_queue) == ((2, 2, 0) if raw else (0, 0, 0))
    assert status.decoded_by_rclpy == (1 if raw else 0)
    assert status.running and status.problem == ""


def test_a_full_queue_counts_dropped_messages_as_lost(nodes):
    talker = nodes.start("talker.py", "--name", "overflow_talker", "--debug")
    talker.expect("ready")
    queue = IntakeQueue(limit=1)
    with live_source(queue=queue) as source:
        assert wait_until(lambda: source.status.publishers >= 1)
        for number in range(3):
            talker.send({"cmd": "log_all", "tag": f"burst{number}"})
            talker.expect("logged")
        assert wait_until(lambda: queue.received >= 15)  # nothing drains the queue: all but one dropped
        assert wait_until(lambda: source.status.lost_queue == queue.dropped)
        status = source.status
    assert status.lost_queue == queue.dropped == queue.received - len(queue) >= 14
    assert status.lost == status.lost_queue


def test_volatile_publishers_are_read_through_the_second_subscription(nodes):
    talker = nodes.start("talker.py", "--name", "volatile_talker", "--volatile")
    talker.expect("ready")
    with live_source() as source:
        assert wait_until(lambda: source.status.publishers >= 1)
        records = log_until_one_arrives(talker, source, "from a volatile node")
        status = source.status
    arrived = [r.msg for r in records if r.msg.startswith("from a volatile node")]
    assert arrived and len(arrived) == len(set(arrived)), "nothing arrived, or something arrived twice"
    assert (status.lost, status.incompatible, status.path) == (0, 0, "c+cdr")


class _OldRclpyHandle:
    """A subscription handle from an rclpy that cannot take serialized messages."""

    def __init__(self, messages):
        self.messages = list(messages)

    def take_message(self, msg_type, raw):
        if raw:
            raise TypeError("take_message() takes 2 positional arguments but 3 were given")
        return (self.messages.pop(0), {}) if self.messages else None


def test_an_rclpy_without_serialized_take_falls_back_to_typed(ros_env, monkeypatch):
    from types import SimpleNamespace

    from rcl_interfaces.msg import Log

    from console_tui.ros.ros2.runtime import RosRuntime
    from console_tui.sources.ros2.loss_counts import LossCounts
    from console_tui.sources.ros2.topic_reader import TopicReader

    take_by("raw+cdr", monkeypatch)
    runtime = RosRuntime()
    try:
        reader = TopicReader(runtime.create_node("fallback"), Log, "/fallback_log", LossCounts())
        assert (reader.path, reader.path_note) == ("raw+cdr", "CONSOLE_TUI_COMPILED_TAKE=0")
        reader.close()
        reader.main = SimpleNamespace(handle=_OldRclpyHandle([Log(name="n", msg="one"), Log(name="n", msg="two")]))
        assert list(reader.take_all(10).msgs) == ["one", "two"]
        assert reader.path == "typed"
    finally:
        runtime.shutdown()


@pytest.mark.parametrize("path", ["c+cdr", "raw+cdr"])
def test_loss_the_middleware_never_reports_is_counted_and_stays_shown_after_the_publisher_left(
    nodes, path, monkeypatch
):
    """With the intake held up, a reader history of 10 keeps the last 10 of a burst of 100
    and Fast DDS reports nothing lost; the gaps in the publisher's sequence numbers do
    (taken in C, or by rclpy where its message info has the publisher's GID)."""
    from console_tui.sources.ros2 import topic_reader as module

    if path == "raw+cdr" and uses_fast_dds_2(os.environ):
        pytest.skip("Jazzy's rclpy gives no publisher GID with a message: gaps cannot be told apart by publisher")
    take_by(path, monkeypatch)
    monkeypatch.setattr(module, "QUEUE_DEPTH", 10)
    # The talker publishes its /rosout itself, so that it can tell when the reader has every
    # message of the burst (in its history of 10, which keeps the last 10), however busy the
    # machine is.
    talker = nodes.start("talker.py", "--name", "gap_talker", "--own-rosout")
    talker.expect("ready")
    queue = StalledQueue()
    with live_source(queue=queue) as source:
        assert wait_until(lambda: source.status.publishers >= 1)
        talker.send({"cmd": "log", "level": "info", "msg": "first: the intake stalls on it"})
        assert queue.stalled.wait(PATIENCE_S)
        talker.send({"cmd": "burst", "count": 100})
        assert talker.expect("burst")["acked"], "the reader never acknowledged the whole burst"
        queue.release.set()
        records = collect(source, lambda got: any(r.msg == "burst 99" for r in got))
        assert [r.msg for r in records][-10:] == [f"burst {n}" for n in range(90, 100)]
        assert wait_until(lambda: source.status.lost_qos == 90), source.status
        talker.stop()
        assert wait_until(lambda: source.status.publishers == 0)
        status = source.status
    assert (status.lost, status.lost_qos) == (90, 90)
    assert status.loss_text() == "90 lost (90 in the middleware)"


@pytest.mark.parametrize("path", ["c+cdr", "raw+cdr"])
def test_a_node_that_logs_as_it_starts_beside_a_volatile_one_arrives_once(nodes, path, monkeypatch):
    """With a VOLATILE publisher on /rosout the second subscription hears every publisher.
    A TRANSIENT_LOCAL node that logs the moment it starts is heard by both subscriptions
    before the periodic look at the graph: its unknown publisher makes the source look at
    the graph at once, and its messages arrive once (from the main subscription). The
    take loop in C gives each message's publisher GID on Jazzy too; rclpy's take there
    does not."""
    if path == "raw+cdr" and uses_fast_dds_2(os.environ):
        pytest.skip("Jazzy's rclpy gives no publisher GID: a node that logs before the graph shows it can arrive twice")
    take_by(path, monkeypatch)
    volatile = nodes.start("talker.py", "--name", "volatile_neighbour", "--volatile")
    volatile.expect("ready")
    with live_source() as source:
        assert wait_until(lambda: source.status.publishers >= 1)
        records = log_until_one_arrives(volatile, source, "volatile")  # the second subscription matched it
        newcomer = nodes.start("talker.py", "--name", "eager_newcomer")
        newcomer.expect("ready")
        newcomer.send({"cmd": "log_all", "tag": "at once"})
        sent = [m["msg"] for m in newcomer.expect("logged")["messages"] if m["level"] >= 20]
        records += collect(source, lambda got: all(any(r.msg == m for r in got) for m in sent))
        records += collect(source, lambda got: False, timeout=1.5)  # anything late, twice
        status = source.status
    got = [r.msg for r in records if r.node == "eager_newcomer"]
    assert sorted(got) == sorted(sent), "every message of the new node once, none twice"
    assert status.lost == 0 and status.publishers == 2


@contextlib.contextmanager
def topic_reader(topic: str = "/rosout"):
    """A ``TopicReader`` on ``topic`` with a node of its own, and its loss counts."""
    from rcl_interfaces.msg import Log

    from console_tui.ros.ros2.runtime import RosRuntime
    from console_tui.sources.ros2.loss_counts import LossCounts
    from console_tui.sources.ros2.topic_reader import TopicReader

    runtime = RosRuntime()
    counts = LossCounts()
    try:
        node = runtime.create_node("reader")
        reader = TopicReader(node, Log, topic, counts)
        yield node, reader, counts
        reader.close()
    finally:
        runtime.shutdown()


def publisher_gid(node, name: str) -> bytes:
    """The GID of node ``name``'s ``/rosout`` publisher, once the graph shows it."""
    from console_tui.sources.ros2.topic_reader import gid_bytes

    found: list[bytes] = []

    def seen() -> bool:
        found[:] = [
            gid_bytes(i.endpoint_gid) for i in node.get_publishers_info_by_topic("/rosout") if i.node_name == name
        ]
        return bool(found)

    assert wait_until(seen), f"{name}'s /rosout publisher never showed in the graph"
    return found[0]


def test_a_message_from_a_publisher_not_seen_yet_makes_the_reader_read_the_graph_again(nodes):
    """The second (VOLATILE) subscription keeps a message only when its publisher is one the
    main subscription cannot match. A publisher newer than the reader's last look at the
    graph is looked up at once (at most every UNKNOWN_PUBLISHER_REFRESH_S)."""
    talker = nodes.start("talker.py", "--name", "graph_newcomer")
    talker.expect("ready")
    with topic_reader() as (node, reader, _counts):
        gid = publisher_gid(node, "graph_newcomer")  # in the graph; the reader has not looked yet
        assert gid not in reader._covered and gid not in reader._uncovered
        assert reader._keep_from_extra({"publisher_gid": gid}) is False, "the main subscription has it"
        assert gid in reader._covered and reader.publisher_count >= 1, "the graph read again"
        stranger = {"publisher_gid": b"\x01" * 16}
        assert reader._keep_from_extra(stranger) is True, "a publisher nobody knows: kept, not lost"
        looked_at = reader._unknown_refreshed_at
        assert reader._keep_from_extra(stranger) is True
        assert reader._unknown_refreshed_at == looked_at, "not read again within the refresh interval"


def test_without_publisher_gids_messages_are_kept_by_the_node_that_owns_their_logger(nodes):
    """An rclpy whose message info has no publisher GID (Jazzy): the second subscription's
    messages are told apart by logger name, the node whose name is the longest prefix."""
    talker = nodes.start("talker.py", "--name", "named_owner")
    talker.expect("ready")
    with topic_reader() as (node, reader, _counts):
        publisher_gid(node, "named_owner")
        assert reader._keep_from_extra({}) is True and reader._gidless
        reader.refresh_graph()
        assert reader._keep_node_from_extra("named_owner") is False
        assert reader._keep_node_from_extra("named_owner.child.grandchild") is False
        assert reader._keep_node_from_extra("named_owner_other") is True
        assert reader._keep_node_from_extra("nobody.at.all") is True


def test_middleware_losses_count_on_the_main_subscription_and_on_the_second_only_when_it_stands_alone(ros_env):
    """Loss events as rclpy hands them (``total_count_change``): the main subscription's count;
    the second one's only while no publisher is covered by the main one (it hears those too)."""
    from types import SimpleNamespace

    with topic_reader("/loss_events") as (_node, reader, counts):
        reader._on_message_lost_main(SimpleNamespace(total_count_change=3))
        assert counts.lost_qos == 3
        reader._on_message_lost_extra(SimpleNamespace(total_count_change=2))
        assert counts.lost_qos == 5, "nothing covered by the main subscription: its losses count"
        reader._covered = {b"\x02" * 16}
        reader._on_message_lost_extra(SimpleNamespace(total_count_change=4))
        assert counts.lost_qos == 5, "not while the main subscription covers a publisher it hears"
        reader._on_incompatible_extra(
            SimpleNamespace(total_count_change=1, last_policy_kind=SimpleNamespace(name="DURABILITY"))
        )
        assert (counts.incompatible, counts.last_policy) == (1, "durability")
        reader._on_incompatible_main(None)
        assert reader.graph_changed


@pytest.mark.parametrize("path", ["c+cdr", "raw+cdr"])
def test_a_lowest_severity_is_asked_of_dds_and_what_it_skips_is_no_loss(nodes, monkeypatch, path):
    """``tail --level error``: the subscriptions carry the content filter ``level >= 40``
    (Fast DDS filters on the writer's side), so DEBUG to WARN never arrive here, and the gaps
    they leave in the talker's sequence numbers are not counted as lost."""
    from rclpy.subscription import Subscription

    from console_tui.sources.ros2.level_filter import NO_RCLPY_FILTER

    content_filters = hasattr(Subscription, "set_content_filter")  # not in Jazzy's rclpy
    raw = take_by(path, monkeypatch)
    talker = nodes.start("talker.py", "--name", "filtered", "--debug")
    talker.expect("ready")
    with live_source(raw=raw, min_level=40) as source:
        logged = []
        for number in range(3):  # each round DEBUG, INFO, WARN, ERROR, FATAL
            talker.send({"cmd": "log_all", "tag": f"round{number}"})
            logged += talker.expect_next("logged")["messages"]
        expected = 6 if content_filters else 15
        records = collect(source, lambda got: sum(r.node == "filtered" for r in got) >= expected)
        time.sleep(0.3)  # what else would come
        records += source.queue.drain()
        status = source.status
    got = [(r.level, r.msg) for r in records if r.node == "filtered"]
    if not content_filters:  # Jazzy: everything comes (the intake process drops)
        assert status.level_filter_note == NO_RCLPY_FILTER
        assert sorted(got) == sorted((m["level"], m["msg"]) for m in logged)
        return
    assert got == [(m["level"], m["msg"]) for m in logged if m["level"] >= 40]
    assert status.min_level == 40 and status.level_filter_note == "", status.level_filter_text()
    assert status.lost == 0 and status.path == path


def test_without_a_content_filter_the_source_says_why(nodes, monkeypatch):
    """Switched off (as on a middleware without content filters): every message arrives,
    and the status says the filter is not the middleware's (the intake process drops them)."""
    from console_tui.sources.ros2.level_filter import SWITCH

    monkeypatch.setenv(SWITCH, "0")
    talker = nodes.start("talker.py", "--name", "unfiltered", "--debug")
    talker.expect("ready")
    with live_source(min_level=40) as source:
        talker.send({"cmd": "log_all", "tag": "all"})
        talker.expect_next("logged")
        records = collect(source, lambda got: sum(r.node == "unfiltered" for r in got) >= 5)
        status = source.status
    assert sorted(r.level for r in records if r.node == "unfiltered") == [10, 20, 30, 40, 50]
    assert status.level_filter_text() == (
        "level >= ERROR: filtered by the intake, not by the middleware "
        f"(the content filter is switched off: {SWITCH}=0)"
    )
