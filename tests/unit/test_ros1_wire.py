"""ROS 1's wire layouts without ROS: the Log decoder, connection headers, framing over a
socket, repeats, the environment, the choice of ROS, XML-RPC timeouts, our slave API."""

from __future__ import annotations

import random
import socket
import struct
import threading
import time
import xmlrpc.client

import pytest

from console_tui.model.formats.ros1_log_msg import MIN_LENGTH, Ros1LogDecoder, Ros1LogError, encode_log
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import ColumnsBuilder, RecordColumns
from console_tui.ros.ros1.environment import DEFAULT_MASTER_URI, Ros1Environment, new_node_name
from console_tui.ros.ros1.master import Ros1CallError, xmlrpc_call
from console_tui.ros.ros1.slave_server import SlaveServer
from console_tui.ros.ros1.tcpros import TcprosError, decode_header, encode_header
from console_tui.ros.ros_version import ROS1, ROS2, choose_ros
from console_tui.sources.ros1.dedupe import Deduplicator
from console_tui.sources.ros1.socket_reader import Connection, Ros1Intake

from support.formats import random_ros1_log


def _framed(message: bytes) -> bytes:
    return struct.pack("<I", len(message)) + message


def _random_message(rng: random.Random) -> tuple[dict, bytes]:
    fields = random_ros1_log(rng)
    return fields, encode_log(**fields)


def _expected(fields: dict, source: str) -> LogRecord:
    return LogRecord(
        fields["stamp_ns"],
        {1: 10, 2: 20, 4: 30, 8: 40, 16: 50}[fields["level"]],
        fields["name"],
        fields["msg"],
        fields["file"],
        fields["function"],
        fields["line"],
        source,
        ",".join(fields["topics"]),
    )


# -- the Log decoder ---------------------------------------------------------------------------


def test_decodes_every_field_of_random_messages():
    rng = random.Random(13)
    decoder = Ros1LogDecoder()
    for _ in range(500):
        fields, data = _random_message(rng)
        assert decoder.decode(data, "/rosout") == _expected(fields, "/rosout")


def test_a_stream_cut_anywhere_gives_the_same_records():
    rng = random.Random(7)
    messages = [_random_message(rng) for _ in range(40)]
    stream = b"".join(_framed(data) for _, data in messages)
    expected = [_expected(fields, "/rosout_agg") for fields, _ in messages]
    for cut_every in (1, 3, 17, 100, 4096):
        decoder = Ros1LogDecoder()
        batch = ColumnsBuilder()
        pending = b""
        for start in range(0, len(stream), cut_every):
            data = pending + stream[start : start + cut_every]
            end = decoder.decode_frames(data, 0, "/rosout_agg", batch, _no_refusal)
            pending = data[end:]
        assert batch.columns().records() == expected and pending == b""


def _no_refusal(_data: bytes, error: Ros1LogError) -> None:
    raise AssertionError(f"refused: {error}")


def test_bad_utf8_and_levels_out_of_range():
    data = encode_log(stamp_ns=5, level=3, name="n", msg="x", file="f", function="g")
    data = data.replace(b"\x01\x00\x00\x00x", b"\x01\x00\x00\x00\xff")
    record = Ros1LogDecoder().decode(data)
    assert record.msg == "\ufffd" and record.level == 20  # bits 1|2: the highest one counts
    assert Ros1LogDecoder().decode(encode_log(stamp_ns=0, level=0, name="", msg="")).level == 10


def test_truncated_and_hostile_messages_are_refused_not_crashing():
    rng = random.Random(3)
    _, data = _random_message(rng)
    decoder = Ros1LogDecoder()
    for size in range(len(data)):
        with pytest.raises(Ros1LogError):
            decoder.decode(data[:size])
    for _ in range(3000):
        junk = bytes(rng.getrandbits(8) for _ in range(rng.randint(MIN_LENGTH, 120)))
        try:
            decoder.decode(junk)
        except Ros1LogError:
            pass
    # a topic count no message could hold
    lying = encode_log(stamp_ns=1, level=2, name="n", msg="m")[:-4] + struct.pack("<I", 10**9)
    with pytest.raises(Ros1LogError, match="topics"):
        decoder.decode(lying)


def test_refused_messages_are_skipped_and_the_stream_goes_on():
    good = encode_log(stamp_ns=1, level=2, name="n", msg="ok")
    stream = _framed(good) + _framed(b"\x00" * 20) + _framed(good)
    refused: list[str] = []
    batch = ColumnsBuilder()
    end = Ros1LogDecoder().decode_frames(stream, 0, "t", batch, lambda _d, e: refused.append(str(e)))
    assert end == len(stream) and batch.msgs == ["ok", "ok"] and len(refused) == 1
    assert batch.sources == ["t", "t"] and batch.columns().topics is None


def test_an_absurd_length_breaks_the_stream():
    with pytest.raises(Ros1LogError, match="announced"):
        Ros1LogDecoder().decode_frames(struct.pack("<I", 1 << 30), 0, "t", ColumnsBuilder(), _no_refusal)


def test_strings_are_shared_between_records():
    decoder = Ros1LogDecoder()
    a = decoder.decode(encode_log(stamp_ns=1, level=2, name="node", msg="a", file="f.cpp", function="fn"))
    b = decoder.decode(encode_log(stamp_ns=2, level=2, name="node", msg="b", file="f.cpp", function="fn"))
    assert a.node is b.node and a.file is b.file and a.function is b.function


# -- connection headers --------------------------------------------------------------------------


def test_connection_headers_round_trip():
    fields = {"callerid": "/n", "topic": "/rosout", "md5sum": "*", "message_definition": "a=b\nc"}
    data = encode_header(fields)
    assert struct.unpack_from("<I", data)[0] == len(data) - 4
    assert decode_header(data[4:]) == fields


@pytest.mark.parametrize("body", [b"\x05\x00\x00\x00ab", b"\x02\x00\x00\x00ab", b"\x01\x00"])
def test_malformed_headers_are_refused(body):
    with pytest.raises(TcprosError):
        decode_header(body)


# -- repeats -------------------------------------------------------------------------------------


def _batch(*keys: tuple[int, str]) -> RecordColumns:
    return RecordColumns.from_records([LogRecord(stamp, 20, node, "m") for stamp, node in keys])


def _stamps(batch: RecordColumns) -> list[int]:
    return list(batch.stamps)


def test_latched_replay_is_recognised_by_node():
    dedupe = Deduplicator()
    dedupe.filter(_batch((1, "/n"), (2, "/n"), (5, "/other")), now=0.0)
    assert dedupe.is_replay((2, "/n", "m")) and not dedupe.is_replay((1, "/n", "m"))
    assert dedupe.is_replay((5, "/other", "m")) and not dedupe.is_replay((2, "/third", "m"))
    assert not dedupe.is_replay((2, "/n", "another text"))


def test_window_drops_repeats_only_while_open():
    dedupe = Deduplicator()
    dedupe.open_window(until=10.0)
    assert _stamps(dedupe.filter(_batch((1, "/n"), (2, "/n")), now=1.0)) == [1, 2]
    kept = dedupe.filter(_batch((2, "/n"), (3, "/n"), (1, "/n")), now=2.0)
    assert kept.records() == [LogRecord(3, 20, "/n", "m")]
    assert dedupe.dropped == 2
    assert _stamps(dedupe.filter(_batch((3, "/n")), now=11.0)) == [3]  # closed: nothing dropped


# -- environment and the choice of ROS -------------------------------------------------------------


def test_environment_as_rospy_reads_it():
    env = Ros1Environment.from_environ({"ROS_MASTER_URI": "http://robot:11311", "ROS_IP": "192.0.2.5"})
    assert (env.master_uri, env.advertise, env.bind, env.master_defaulted) == (
        "http://robot:11311",
        "192.0.2.5",
        "192.0.2.5",
        False,
    )
    env = Ros1Environment.from_environ({"ROS_HOSTNAME": "laptop.local", "ROS_IP": "192.0.2.5"})
    assert (env.master_uri, env.advertise, env.bind, env.master_defaulted) == (
        DEFAULT_MASTER_URI,
        "laptop.local",
        "0.0.0.0",
        True,
    )
    assert Ros1Environment.from_environ({"ROS_IP": "127.0.0.1"}).bind == "127.0.0.1"
    assert Ros1Environment.from_environ({"ROS_HOSTNAME": "localhost"}).bind == "127.0.0.1"
    assert Ros1Environment.from_environ({}).advertise  # the host name, never empty
    first, second = new_node_name(), new_node_name()
    assert first != second and first.startswith("/console_tui_")


def test_choice_of_ros():
    never = lambda _uri: pytest.fail("no master should be asked")  # noqa: E731
    assert choose_ros(1, {}, master_answers=never).version == ROS1
    assert choose_ros(2, {"ROS_VERSION": "1"}, master_answers=never).version == ROS2
    assert choose_ros(None, {"ROS_VERSION": "1"}, master_answers=never).reason == "ROS_VERSION=1"
    assert choose_ros(None, {}, master_answers=never).version == ROS2
    answers = lambda _uri: True  # noqa: E731
    silent = lambda _uri: False  # noqa: E731
    master = {"ROS_MASTER_URI": "http://m:11311"}
    assert choose_ros(None, master, master_answers=answers).version == ROS1
    assert choose_ros(None, master, master_answers=silent, has_rclpy=lambda: True).version == ROS2
    # a ROS 1 user without rclpy is never sent to install it
    assert choose_ros(None, master, master_answers=silent, has_rclpy=lambda: False).version == ROS1


# -- XML-RPC with timeouts --------------------------------------------------------------------------


def test_a_silent_server_times_out():
    with socket.socket() as server:
        server.bind(("127.0.0.1", 0))
        server.listen()
        uri = f"http://127.0.0.1:{server.getsockname()[1]}/"
        with pytest.raises(Ros1CallError) as caught:
            xmlrpc_call(uri, "getPid", "/me", timeout=0.3)
        assert caught.value.unreachable and "no answer within 0.3 s" in str(caught.value)


def test_nothing_listening_is_refused():
    with socket.socket() as free:
        free.bind(("127.0.0.1", 0))
        port = free.getsockname()[1]
    with pytest.raises(Ros1CallError, match="refused") as caught:
        xmlrpc_call(f"http://127.0.0.1:{port}/", "getPid", "/me", timeout=1.0)
    assert caught.value.unreachable


class _Node:
    def __init__(self) -> None:
        self.updates: list = []
        self.shutdowns: list = []

    def bus_info(self):
        return [[1, "http://pub:1/", "i", "TCPROS", "/rosout", True, ""]]

    def bus_stats(self):
        return [["/rosout", [[1, 100, 0, True]]]]

    def subscriptions(self):
        return [["/rosout", "rosgraph_msgs/Log"]]

    def publisher_update(self, topic, publishers):
        self.updates.append((topic, publishers))

    def shutdown_requested(self, caller_id, reason):
        self.shutdowns.append((caller_id, reason))


def test_slave_api_answers_as_a_node():
    node = _Node()
    environment = Ros1Environment("http://master:11311/", "127.0.0.1", "127.0.0.1")
    server = SlaveServer(environment, node)
    server.start()
    try:
        proxy = xmlrpc.client.ServerProxy(server.uri)
        assert proxy.getPid("/rosnode")[2] > 0
        assert proxy.getMasterUri("/x") == [1, "", "http://master:11311/"]
        assert proxy.getBusInfo("/x")[2] == node.bus_info()
        assert proxy.getSubscriptions("/x")[2] == [["/rosout", "rosgraph_msgs/Log"]]
        assert proxy.getPublications("/x")[2] == []
        assert proxy.requestTopic("/x", "/rosout", [["TCPROS"]])[0] == 0
        assert proxy.publisherUpdate("/master", "/rosout", ["http://a:1/"])[0] == 1
        assert proxy.shutdown("/rosnode", "kill") == [1, "shutdown", 0]
        assert node.updates == [("/rosout", ["http://a:1/"])] and node.shutdowns == [("/rosnode", "kill")]
    finally:
        server.close()


# -- the intake over a real socket ---------------------------------------------------------------


def test_intake_reads_frames_drops_a_latched_replay_and_reports_the_end():
    queue = IntakeQueue()
    closed: list = []
    done = threading.Event()
    intake = Ros1Intake(queue, on_closed=lambda c, reason: (closed.append((c.caller_id, reason)), done.set()))
    intake.start()
    ours, theirs = socket.socketpair()
    try:
        message = encode_log(stamp_ns=7, level=4, name="/n", msg="first", topics=["/t"])
        intake.add(Connection(ours, "/rosout", "http://n:1/", "/n"))
        data = _framed(message) * 1 + _framed(encode_log(stamp_ns=8, level=8, name="/n", msg="second"))
        for start in range(0, len(data), 5):
            theirs.sendall(data[start : start + 5])
            time.sleep(0.001)
        records = _drain_until(queue, 2)
        assert [(r.msg, r.level, r.topics) for r in records] == [("first", 30, "/t"), ("second", 40, "")]
        # a new connection from the same node, latched: starts with its last message again
        again_ours, again_theirs = socket.socketpair()
        intake.add(Connection(again_ours, "/rosout", "http://n:1/", "/n"))
        again_theirs.sendall(_framed(encode_log(stamp_ns=8, level=8, name="/n", msg="second")))
        again_theirs.sendall(_framed(encode_log(stamp_ns=9, level=2, name="/n", msg="third")))
        assert [r.msg for r in _drain_until(queue, 1)] == ["third"]
        theirs.sendall(struct.pack("<I", 1 << 30))  # a broken stream ends its connection
        assert done.wait(5)
        assert closed[0][0] == "/n" and "announced" in closed[0][1] and "broken" in intake.last_problem
        again_theirs.close()
    finally:
        intake.stop()
        theirs.close()


def _drain_until(queue: IntakeQueue, count: int, timeout: float = 60.0) -> list[LogRecord]:
    records: list[LogRecord] = []
    deadline = time.monotonic() + timeout
    while len(records) < count and time.monotonic() < deadline:
        records += queue.drain()
        time.sleep(0.01)
    time.sleep(0.05)
    return records + queue.drain()
