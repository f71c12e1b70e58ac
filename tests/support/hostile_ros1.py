"""Hostile ROS 1 peers on 127.0.0.1 for tests: a master and publishers that answer as a test
tells them to (malformed, dripping, huge), written on plain sockets so that nothing in them
is bounded unless the client bounds it.

``FakeMaster(answers)``: an XML-RPC master; ``answers[method]`` is a value (answered as
``[1, "", value]``), a list of values taken one per call (the last one kept), or a
``Reply`` (raw bytes, sent as told). ``FakePublisher``: a node's slave API answering
``requestTopic`` and a TCPROS server sending ``rosgraph_msgs/Log`` messages from a node name.
"""

from __future__ import annotations

import itertools
import socket
import struct
import threading
import time
import xmlrpc.client
from collections import Counter
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from console_tui.model.formats.ros1_log_msg import encode_log
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.ros.ros1.environment import Ros1Environment
from console_tui.ros.ros1.tcpros import decode_header, encode_header
from console_tui.sources.ros1.live_source import Ros1LiveSource


@dataclass
class Reply:
    """Raw bytes for an answer: what ``chunks()`` gives (afresh for each call), sent one
    after another, ``pause`` s apart."""

    chunks: Callable[[], Iterable[bytes]]
    pause: float = 0.0


def xml_answer(value: Any) -> bytes:
    return xmlrpc.client.dumps(([1, "", value],), methodresponse=True).encode()


def http_answer(body: bytes) -> bytes:
    return b"HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\nContent-Length: %d\r\n\r\n" % len(body) + body


def drip(value: Any, pause: float = 0.2) -> Reply:
    """A whole, correct answer sent one byte at a time, ``pause`` s apart."""
    data = http_answer(xml_answer(value))
    return Reply(lambda: (data[i : i + 1] for i in range(len(data))), pause)


def huge_system_state(total_bytes: int, node: str = "/n") -> Reply:
    """A valid ``getSystemState`` answer of about ``total_bytes``, made as it is sent."""
    row = f"<value><array><data><value><string>/t{{}}</string></value><value><array><data><value><string>{node}</string></value></data></array></value></data></array></value>"
    head = b"<?xml version='1.0'?><methodResponse><params><param><value><array><data><value><int>1</int></value><value><string></string></value><value><array><data><value><array><data>"
    tail = b"</data></array></value><value><array><data></data></array></value><value><array><data></data></array></value></data></array></value></data></array></value></param></params></methodResponse>"

    chunk = "".join(row.format(n) for n in range(5000)).encode()  # made once: sending costs no Python work

    def chunks() -> Iterator[bytes]:
        yield b"HTTP/1.0 200 OK\r\nContent-Type: text/xml\r\n\r\n" + head
        for _ in range(total_bytes // len(chunk) + 1):
            yield chunk
        yield tail

    return Reply(chunks)


class _Server:
    """A listening socket on 127.0.0.1 with a thread per connection."""

    def __init__(self) -> None:
        self.listener = socket.socket()
        self.listener.bind(("127.0.0.1", 0))
        self.listener.listen(64)
        self.port = self.listener.getsockname()[1]
        self.closed = threading.Event()
        self.sockets: list[socket.socket] = []
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self) -> None:
        while not self.closed.is_set():
            try:
                sock, _ = self.listener.accept()
            except OSError:
                return
            self.sockets.append(sock)
            threading.Thread(target=self._serve_guarded, args=(sock,), daemon=True).start()

    def _serve_guarded(self, sock: socket.socket) -> None:
        try:
            self.serve(sock)
        except OSError:
            pass
        finally:
            sock.close()

    def serve(self, sock: socket.socket) -> None:
        raise NotImplementedError

    def close(self) -> None:
        self.closed.set()
        self.listener.close()
        for sock in self.sockets:
            try:
                sock.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass

    def __enter__(self):
        return self

    def __exit__(self, *_exc) -> None:
        self.close()


def _read_request(sock: socket.socket) -> tuple[str, tuple]:
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = sock.recv(65536)
        if not chunk:
            raise OSError("closed")
        data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    length = next(
        int(line.split(b":")[1]) for line in head.split(b"\r\n") if line.lower().startswith(b"content-length")
    )
    while len(body) < length:
        chunk = sock.recv(65536)
        if not chunk:
            raise OSError("closed")
        body += chunk
    params, method = xmlrpc.client.loads(body)
    return str(method), params


class XmlRpcPeer(_Server):
    """Answers each XML-RPC method as ``answers`` says; counts the calls (``calls``)."""

    def __init__(self, answers: dict[str, Any]) -> None:
        self.answers = dict(answers)
        self.calls: Counter[str] = Counter()
        #: Calls by ``(method, caller id)``.
        self.callers: Counter[tuple[str, str]] = Counter()
        super().__init__()
        self.uri = f"http://127.0.0.1:{self.port}/"

    def answer(self, method: str, params: tuple) -> Any:
        answer = self.answers.get(method)
        if callable(answer):
            answer = answer(*params)
        if isinstance(answer, _Seq):
            answer = answer.next()
        return answer

    def serve(self, sock: socket.socket) -> None:
        method, params = _read_request(sock)
        self.calls[method] += 1
        self.callers[(method, str(params[0]) if params else "")] += 1
        answer = self.answer(method, params)
        if isinstance(answer, Reply):
            for chunk in answer.chunks():
                if self.closed.is_set():
                    return
                sock.sendall(chunk)
                if answer.pause:
                    time.sleep(answer.pause)
        else:
            sock.sendall(http_answer(xml_answer(answer)))


class _Seq:
    """Answers taken in turn, the last one kept."""

    def __init__(self, values: list[Any]) -> None:
        self.values = list(values)
        self.lock = threading.Lock()

    def next(self) -> Any:
        with self.lock:
            return self.values.pop(0) if len(self.values) > 1 else self.values[0]


def in_turn(*values: Any) -> _Seq:
    return _Seq(list(values))


class FakeMaster(XmlRpcPeer):
    """A master: a correct one by default (``getPid``, ``getParam``, ``registerSubscriber``
    listing ``publishers``, ``getSystemState``), each answer replaceable."""

    def __init__(self, publishers: list[str] | None = None, **answers: Any) -> None:
        self.publishers = publishers if publishers is not None else []
        defaults: dict[str, Any] = {
            "getPid": 4242,
            "getParam": "run-1",
            "getUri": "http://127.0.0.1:1/",
            "registerSubscriber": lambda *_args: list(self.publishers),
            "unregisterSubscriber": 1,
            "getSystemState": lambda *_args: [[["/rosout", self.publishers and ["/good"]]], [], []],
        }
        super().__init__({**defaults, **answers})


@dataclass
class FakePublisher:
    """A node ``name`` publishing ``/rosout``: its slave API answers ``requestTopic`` (as
    ``request_topic`` says, by default correctly) and its TCPROS server sends one Log
    message every ``period`` s, numbered, until closed."""

    name: str = "/good"
    period: float = 0.05
    request_topic: Any = None
    stream: Callable[[socket.socket], None] | None = None
    sent: int = 0
    _servers: list[_Server] = field(default_factory=list)

    def __post_init__(self) -> None:
        tcp = _Tcpros(self)
        slave = XmlRpcPeer({"requestTopic": self.request_topic or ["TCPROS", "127.0.0.1", tcp.port], "getPid": 1})
        self._servers = [tcp, slave]
        self.uri = slave.uri
        self.slave = slave

    def close(self) -> None:
        for server in self._servers:
            server.close()

    def __enter__(self) -> FakePublisher:
        return self

    def __exit__(self, *_exc) -> None:
        self.close()


class _Tcpros(_Server):
    def __init__(self, publisher: FakePublisher) -> None:
        self.publisher = publisher
        super().__init__()

    def serve(self, sock: socket.socket) -> None:
        (length,) = struct.unpack("<I", _exact(sock, 4))
        decode_header(_exact(sock, length))
        if self.publisher.stream is not None:
            self.publisher.stream(sock)
            return
        header = {"callerid": self.publisher.name, "topic": "/rosout", "type": "rosgraph_msgs/Log"}
        sock.sendall(encode_header(header))
        for n in itertools.count():
            if self.closed.is_set():
                return
            message = encode_log(stamp_ns=n + 1, level=2, name=self.publisher.name, msg=f"good {n}")
            sock.sendall(struct.pack("<I", len(message)) + message)
            self.publisher.sent += 1
            time.sleep(self.publisher.period)


def _exact(sock: socket.socket, count: int) -> bytes:
    data = b""
    while len(data) < count:
        chunk = sock.recv(count - len(data))
        if not chunk:
            raise OSError("closed")
        data += chunk
    return data


def rss_peak_mb() -> float:
    """This process's peak resident memory since ``reset_rss_peak`` (MB)."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    raise AssertionError("no VmHWM")


def reset_rss_peak() -> None:
    with open("/proc/self/clear_refs", "w") as refs:
        refs.write("5")


class RunningSource:
    """A ``Ros1LiveSource`` reading from ``master``; ``records`` so far."""

    def __init__(self, master: FakeMaster, topic: str | None = None, call_timeout: float = 1.0) -> None:
        environment = Ros1Environment(master.uri, "127.0.0.1", "127.0.0.1")
        self.queue = IntakeQueue()
        self.source = Ros1LiveSource(self.queue, topic, environment, call_timeout=call_timeout)
        self.records: list = []

    def __enter__(self) -> RunningSource:
        self.source.start()
        return self

    def __exit__(self, *_exc) -> None:
        self.source.stop()

    def good_rows(self) -> int:
        self.records.extend(self.queue.drain())
        return sum(1 for r in self.records if r.node == "/good" and r.msg.startswith("good "))
