"""The ROS 1 intake thread: every open TCPROS log connection read, decoded, handed on.

One thread waits on all the connections' sockets at once (``selectors``), reads what each
has (up to ``RECV_BYTES`` at a time), decodes the whole messages straight from the bytes
received into columns (``Ros1LogDecoder.decode_frames``, through the frame loop in C once
``compiled_frames`` has built it: until then, or without a compiler, in Python), drops repeats (``Deduplicator``) and puts one
batch per turn into the ``IntakeQueue`` (``_deliver``, the one hand-off). When only a
trickle arrives it pauses after a turn (``coalesce.Coalescer``), so a turn pays for more
than one message.

Connections are added and closed from other threads (``add``, ``close_topic``); a
connection that ends (the publisher went away, or sent a broken stream) is reported to
``on_closed(connection, reason)`` on this thread.
"""

from __future__ import annotations

import itertools
import selectors
import socket
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from ...model.formats.ros1_log_msg import Ros1LogDecoder, Ros1LogError
from ...model.store.intake_queue import IntakeQueue
from ...model.store.record_batch import ColumnsBuilder, RecordColumns
from ...system.thread_names import os_named
from ..coalesce import Coalescer
from . import compiled_frames
from .dedupe import Deduplicator

RECV_BYTES = 1 << 18
SELECT_TIMEOUT_S = 0.2
_ids = itertools.count(1)
#: Why a connection ended: the publisher closed it between messages (a plain end), or in one.
CLOSED = "the publisher closed the connection"
CLOSED_MID_MESSAGE = "the publisher closed the connection in the middle of a message"


@dataclass(eq=False)
class Connection:
    """One TCPROS connection to a publisher of a log topic."""

    sock: socket.socket
    topic: str
    #: The publisher's slave API URI (as the master lists it).
    publisher: str
    #: The publisher's node name, from its connection header.
    caller_id: str
    id: int = field(default_factory=lambda: next(_ids))
    bytes_received: int = 0
    messages: int = 0
    #: Bytes of a message not complete yet.
    pending: bytes = b""


class Ros1Intake:
    """Reads connections in a thread of its own into ``queue``; ``start``, ``add``, ``stop``."""

    def __init__(
        self,
        queue: IntakeQueue,
        on_closed: Callable[[Connection, str], None] = lambda _connection, _reason: None,
    ) -> None:
        self.queue = queue
        self.on_closed = on_closed
        self.decoder = Ros1LogDecoder()
        #: Why the frame loop in C is not used (or how it was built); "" while it is built.
        self.compiled_note = ""
        self._compiled_pending = True
        self.dedupe = Deduplicator()
        #: Messages neither decodable nor recoverable; read from any thread.
        self.lost_undecodable = 0
        self.last_problem = ""
        self._selector = selectors.DefaultSelector()
        self._wake_r, self._wake_w = socket.socketpair()
        self._wake_r.setblocking(False)
        self._wake_w.setblocking(False)
        self._selector.register(self._wake_r, selectors.EVENT_READ, None)
        self._lock = threading.Lock()
        self._commands: list[Callable[[], None]] = []
        self._connections: dict[int, Connection] = {}
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    # -- any thread ----------------------------------------------------------------------------

    def start(self) -> None:
        compiled_frames.start_loading()
        self._thread = threading.Thread(target=os_named(self._run), name="console-tui-ros1-intake", daemon=True)
        self._thread.start()

    def stop(self, timeout: float = 2.0) -> None:
        self._stop.set()
        self._wake()
        if self._thread is not None:
            self._thread.join(timeout)
        for connection in list(self._connections.values()):
            _close(connection.sock)
        self._connections.clear()
        try:
            self._selector.close()
        except Exception:
            pass
        self._wake_r.close()
        self._wake_w.close()

    def add(self, connection: Connection) -> None:
        """Start reading ``connection`` (its socket is made non-blocking here)."""
        connection.sock.setblocking(False)
        self._command(lambda: self._add(connection))

    def close_topic(self, topic: str) -> None:
        """Close every connection of ``topic`` (without reporting them closed)."""
        self._command(lambda: self._close_where(lambda c: c.topic == topic))

    def close_publisher(self, topic: str, publisher: str) -> None:
        self._command(lambda: self._close_where(lambda c: c.topic == topic and c.publisher == publisher))

    def dedupe_for(self, seconds: float) -> None:
        """Check every message against the others for ``seconds`` from now (topics overlapping)."""
        until = time.monotonic() + seconds
        self._command(lambda: self.dedupe.open_window(until))

    def connections(self) -> list[Connection]:
        """A snapshot of the open connections."""
        with self._lock:
            return list(self._connections.values())

    def _command(self, command: Callable[[], None]) -> None:
        with self._lock:
            self._commands.append(command)
        self._wake()

    def _wake(self) -> None:
        try:
            self._wake_w.send(b"\0")
        except OSError:  # full (it will wake anyway) or closed
            pass

    # -- the intake thread --------------------------------------------------------------------

    def _add(self, connection: Connection) -> None:
        with self._lock:
            self._connections[connection.id] = connection
        self._selector.register(connection.sock, selectors.EVENT_READ, connection)

    def _close_where(self, condition: Callable[[Connection], bool]) -> None:
        for connection in [c for c in self._connections.values() if condition(c)]:
            self._forget(connection)

    def _forget(self, connection: Connection) -> None:
        with self._lock:
            self._connections.pop(connection.id, None)
        try:
            self._selector.unregister(connection.sock)
        except (KeyError, ValueError, OSError):
            pass
        _close(connection.sock)

    def _ended(self, connection: Connection, reason: str) -> None:
        self._forget(connection)
        self.on_closed(connection, reason)

    def _run(self) -> None:
        select = self._selector.select
        decode = self.decoder.decode_frames
        coalescer = Coalescer()
        while not self._stop.is_set():
            if self._compiled_pending:
                self._adopt_compiled()
            try:
                events = select(SELECT_TIMEOUT_S)
            except OSError:  # the selector closed under us: stopping
                break
            batch = ColumnsBuilder()
            for key, _mask in events:
                connection = key.data
                if connection is None:
                    self._run_commands()
                    continue
                try:
                    data = connection.sock.recv(RECV_BYTES)
                except (BlockingIOError, InterruptedError):
                    continue
                except OSError as error:
                    self._ended(connection, error.strerror or str(error))
                    continue
                if not data:
                    cut = len(connection.pending)
                    self._ended(connection, f"{CLOSED_MID_MESSAGE} ({cut:,} bytes of it came)" if cut else CLOSED)
                    continue
                connection.bytes_received += len(data)
                if connection.pending:
                    data = connection.pending + data
                first = len(batch)
                try:
                    end = decode(data, 0, connection.topic, batch, self._refused)
                except Ros1LogError as error:
                    batch.cut(first)
                    self.last_problem = f"{connection.caller_id} sent a broken {connection.topic} stream: {error}"
                    self._ended(connection, str(error))
                    continue
                connection.pending = data[end:] if end < len(data) else b""
                if connection.messages == 0 and len(batch) > first and self.dedupe.is_replay(batch.key(first)):
                    batch.drop(first)
                    self.dedupe.dropped += 1
                connection.messages += len(batch) - first
            if batch:
                self._deliver(self.dedupe.filter(batch.columns(), time.monotonic()))
            pause = coalescer.after(len(batch))
            if pause:
                self._stop.wait(pause)

    def _adopt_compiled(self) -> None:
        """Decode through the frame loop in C from the moment its build is done."""
        done = compiled_frames.loaded_now()
        if done is not None:
            self._compiled_pending = False
            self.decoder.frame_loop, self.compiled_note = done

    @property
    def compiled(self) -> bool:
        """Whether the frame loop in C decodes the frames (else the Python decoder alone)."""
        return self.decoder.frame_loop is not None

    def _deliver(self, batch: RecordColumns) -> None:
        """The one hand-off to the rest of the app."""
        self.queue.put(batch)

    def _refused(self, _data: bytes, error: Ros1LogError) -> None:
        self.lost_undecodable += 1
        self.last_problem = f"a log message could not be read: {error}"

    def _run_commands(self) -> None:
        try:
            while self._wake_r.recv(4096):
                pass
        except (BlockingIOError, InterruptedError, OSError):
            pass
        with self._lock:
            commands, self._commands = self._commands, []
        for command in commands:
            command()


def _close(sock: socket.socket) -> None:
    try:
        sock.close()
    except OSError:
        pass
