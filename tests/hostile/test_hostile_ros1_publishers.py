"""Hostile ROS 1 publishers (issue 33, items 4 and 11): real TCPROS servers on 127.0.0.1 that
break their stream or drip their header, and more publishers than connections allowed. The
status says which publisher is not read and why; the good publisher's rows arrive."""

from __future__ import annotations

import socket
import struct
import time

import pytest

from console_tui.model.formats.ros1_log_msg import encode_log
from console_tui.ros.ros1.tcpros import encode_header
from console_tui.sources.ros1 import subscribed_topic

from support.hostile_ros1 import FakeMaster, FakePublisher, RunningSource
from support.ros1 import wait_for


def _header(sock: socket.socket, name: str) -> None:
    sock.sendall(encode_header({"callerid": name, "topic": "/rosout", "type": "rosgraph_msgs/Log"}))


def _four_gigabytes(sock: socket.socket) -> None:
    _header(sock, "/huge")
    sock.sendall(struct.pack("<I", 0xFFFFFFF0))
    sock.recv(1)  # until the subscriber hangs up


def _closed_mid_message(sock: socket.socket) -> None:
    _header(sock, "/cut")
    message = encode_log(stamp_ns=1, level=2, name="/cut", msg="never whole")
    sock.sendall(struct.pack("<I", len(message)) + message[:10])


def _dripping_header(sock: socket.socket) -> None:
    data = encode_header({"callerid": "/drip", "topic": "/rosout", "type": "rosgraph_msgs/Log"})
    for byte in data:
        sock.sendall(bytes([byte]))
        time.sleep(0.2)


@pytest.mark.parametrize(
    ("stream", "said"),
    [
        (_four_gigabytes, "bytes announced"),
        (_closed_mid_message, "in the middle of a message"),
        (_dripping_header, "no answer in time"),
    ],
    ids=["4GB-length", "closed-mid-message", "dripping-header"],
)
def test_a_broken_publisher_is_named_with_its_reason(stream, said):
    with (
        FakePublisher() as good,
        FakePublisher(name="/bad", stream=stream) as bad,
        FakeMaster([good.uri, bad.uri]) as master,
        RunningSource(master, topic="/rosout") as running,
    ):
        wait_for(lambda: running.good_rows() >= 3, 30, "the good publisher's rows")
        wait_for(lambda: said in running.source.status.problem, 30, f"{said!r} in the status")
        status = running.source.status
        assert status.running and f"publisher {bad.uri} not read" in status.problem
        assert status.publishers == 1


def test_connections_are_bounded_and_the_rest_counted(monkeypatch):
    monkeypatch.setattr(subscribed_topic, "MAX_CONNECTIONS", 3)
    publishers = [FakePublisher(name=f"/p{i}", period=0.2) for i in range(5)]
    try:
        with FakeMaster([p.uri for p in publishers]) as master, RunningSource(master, topic="/rosout") as running:
            wait_for(lambda: running.source.status.publishers == 3, 30, "three connections")
            wait_for(lambda: "2 publishers not read" in running.source.status.problem, 30, "the count")
            assert "at most 3 connections at once" in running.source.status.problem
            assert sum(p.slave.calls["requestTopic"] for p in publishers) == 3
            assert running.source.status.running
    finally:
        for publisher in publishers:
            publisher.close()
