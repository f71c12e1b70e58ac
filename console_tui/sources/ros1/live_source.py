"""The live ROS 1 log stream: ``/rosout_agg`` or ``/rosout`` from a ROS 1 master, natively.

The console is a ROS 1 node named ``/console_tui_<pid>_<n>``: it serves the slave API
(``SlaveServer``), registers as a subscriber of the log topic with the master, asks each
publisher for a TCPROS connection and reads them all in one intake thread (``Ros1Intake``).
Which topic: the one asked for, else ``/rosout_agg`` while a rosout node publishes it that
can be reached, else every node's ``/rosout`` directly. Moving between the two, both are
read for a moment and repeats are dropped.

A graph thread does everything that waits on the network (each call with a timeout):

- the master unreachable: the status says "waiting for master at URI" at once and the
  thread tries again every ``MASTER_RETRY_S`` while the app runs;
- the master restarted (its ``/run_id`` or pid changed): register again and connect to the
  publishers the new master knows; connections still open stay open;
- publishers that appear later come with the master's ``publisherUpdate``; one whose
  connection ends is tried again (backing off, ``SubscribedTopic``) while the master lists
  it; a killed node's stale registration (connection refused) is skipped quietly;
- a publisher that refuses the subscription (another type, wrong md5sum) is reported;
- ``rosnode kill`` (our ``shutdown``) ends the source; the table keeps what it has.

``stop`` unregisters from the master and closes everything.
"""

from __future__ import annotations

import queue
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from ...model.formats.ros1_log_msg import MD5SUM, TYPE
from ...model.store.intake_queue import IntakeQueue
from ...ros.ros1.environment import Ros1Environment, new_node_name
from ...ros.ros1.master import CALL_TIMEOUT_S, Master, Ros1CallError, xmlrpc_call
from ...ros.ros1.slave_server import SlaveServer
from ...ros.ros1.tcpros import TcprosError, open_subscription
from ...ros.ros1.xmlrpc import shown
from ...system.thread_names import os_named
from ..log_topics import ROSOUT, ROSOUT_AGG
from ..status import SourceStatus
from .socket_reader import CLOSED, Connection, Ros1Intake
from .subscribed_topic import SubscribedTopic, connection_room, not_read_text

GRAPH_PERIOD_S = 1.0
MASTER_RETRY_S = 1.0
#: A refused ``getSystemState`` (malformed, too large) is asked again after 1, 2, 4 ... s, this at most.
STATE_RETRY_MAX_S = 30.0
#: How long both topics are read when moving between /rosout and /rosout_agg, at most.
OVERLAP_S = 6.0
#: Both are read until the new topic has delivered messages for this long: a rosout node's
#: ``/rosout_agg`` may be connected before it has connected to the nodes it relays.
RELAY_SETTLE_S = 1.0
#: Publishers asked for a connection at once; a slow one holds a worker for its calls'
#: timeouts at most, and retries back off, so slow peers cannot keep the others waiting long.
CONNECT_WORKERS = 16
UNREGISTER_TIMEOUT_S = 1.0
PATH = "tcpros"
#: The path once the frame loop in C decodes the frames (``compiled_frames``).
PATH_COMPILED = "c+tcpros"


class Ros1LiveSource:
    """Reads a ROS 1 log topic into an ``IntakeQueue``; ``start``, ``stop``, ``status``."""

    def __init__(
        self,
        queue_: IntakeQueue,
        topic: str | None = None,
        environment: Ros1Environment | None = None,
        *,
        call_timeout: float = CALL_TIMEOUT_S,
    ) -> None:
        self.queue = queue_
        self.requested_topic = topic
        self.environment = environment or Ros1Environment.from_environ()
        self.call_timeout = call_timeout
        self.node_name = new_node_name()
        origin = f"ROS 1 {self.environment.master_uri}"
        self.status = SourceStatus(topic=topic or "", path=PATH, origin=origin)
        #: The master's restarts seen while running.
        self.master_restarts = 0
        self._events: queue.Queue[tuple[Any, ...]] = queue.Queue()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._topics: dict[str, SubscribedTopic] = {}
        self._topic_names: tuple[str, ...] = ()
        self._current = topic or ""
        self._retiring: tuple[str, float] | None = None
        #: When the topic moved to first delivered a message (while the old one is retiring).
        self._delivering_since: float | None = None
        self._dead_agg: frozenset[str] = frozenset()
        #: The master's ``/run_id`` and pid when last reached; a change means it restarted.
        self._master_key: tuple[str, int] | None = None
        self._master_ok = False
        self._master_problem = ""
        #: After a refused ``getSystemState``: when to ask again, the wait, and why.
        self._state_after = 0.0
        self._state_backoff = 0.0
        self._state_problem = ""
        self._ended = ""
        self._server: SlaveServer | None = None
        self._intake: Ros1Intake | None = None
        self._pool: ThreadPoolExecutor | None = None
        self._master = Master(self.environment.master_uri, self.node_name, call_timeout)

    # -- control ---------------------------------------------------------------------------------

    def start(self) -> None:
        self._set_status(running=True, problem=self._waiting(""))
        self._thread = threading.Thread(target=os_named(self._run_guarded), name="console-tui-ros1-graph", daemon=True)
        self._thread.start()

    def stop(self, timeout: float = 4.0) -> None:
        self._stop.set()
        self._events.put(("wake",))
        if self._thread is not None:
            self._thread.join(timeout)

    @property
    def slave_uri(self) -> str:
        return self._server.uri if self._server is not None else ""

    # -- the slave API's questions (server threads) -------------------------------------------------

    def bus_info(self) -> list[list[Any]]:
        intake = self._intake
        connections = intake.connections() if intake is not None else []
        return [
            [c.id, c.publisher, "i", "TCPROS", c.topic, True, f"TCPROS connection to [{c.caller_id}]"]
            for c in connections
        ]

    def bus_stats(self) -> list[list[Any]]:
        intake = self._intake
        connections = intake.connections() if intake is not None else []
        return [
            [topic, [[c.id, c.bytes_received, 0, True] for c in connections if c.topic == topic]]
            for topic in self._topic_names
        ]

    def subscriptions(self) -> list[list[str]]:
        return [[topic, TYPE] for topic in self._topic_names]

    def publisher_update(self, topic: str, publishers: list[str]) -> None:
        self._events.put(("update", topic, publishers))

    def shutdown_requested(self, caller_id: str, reason: str) -> None:
        self._events.put(("shutdown", caller_id, reason))

    # -- the graph thread ------------------------------------------------------------------------

    def _set_status(self, **changes: Any) -> None:
        self.status = SourceStatus(**{**self.status.__dict__, **changes})

    def _run_guarded(self) -> None:
        try:
            self._run()
        except Exception as error:  # the app must learn of it, never die of it
            self._ended = f"ROS 1 intake stopped: {type(error).__name__}: {error}"
        finally:
            self._close_all()
            self._set_status(running=False, problem=self._ended, publishers=0)

    def _run(self) -> None:
        try:
            self._server = SlaveServer(self.environment, self)
        except OSError as error:
            self._ended = (
                f"cannot listen on {self.environment.bind}: {error.strerror or error} (check ROS_IP / ROS_HOSTNAME)"
            )
            return
        self._server.start()
        self._intake = Ros1Intake(self.queue, on_closed=self._on_closed)
        self._intake.start()
        self._pool = ThreadPoolExecutor(CONNECT_WORKERS, thread_name_prefix="console-tui-ros1-connect")
        next_check = 0.0
        while not self._stop.is_set() and not self._ended:
            now = time.monotonic()
            if now >= next_check:
                self._check_master()
                next_check = time.monotonic() + (GRAPH_PERIOD_S if self._master_ok else MASTER_RETRY_S)
            self._retire_if_ready()
            self._connect_due()
            self._show()
            wait = max(0.01, min(next_check - time.monotonic(), self._next_retry() - time.monotonic(), 0.5))
            try:
                event = self._events.get(timeout=wait)
            except queue.Empty:
                continue
            self._handle(event)
            while True:
                try:
                    self._handle(self._events.get_nowait())
                except queue.Empty:
                    break

    # -- the master -------------------------------------------------------------------------------

    def _check_master(self) -> None:
        master = self._master
        try:
            key = (master.run_id(), master.pid())
            if key != self._master_key:
                if self._master_key is not None:
                    self.master_restarts += 1
                for topic in self._topics.values():
                    topic.registered = False
                self._master_key = key
            problem = ""
            if self.requested_topic is None and time.monotonic() >= self._state_after:
                try:
                    self._choose_topic(master.system_state().publishers.get(ROSOUT_AGG, []))
                    self._state_backoff = 0.0
                except Ros1CallError as error:
                    if error.unreachable:
                        raise
                    # The graph unknown this time: keep the topic read so far, ask later.
                    problem = self._state_problem = error.reason
                    self._current = self._current or ROSOUT
                    self._state_backoff = min(self._state_backoff * 2 or MASTER_RETRY_S, STATE_RETRY_MAX_S)
                    self._state_after = time.monotonic() + self._state_backoff
            elif self.requested_topic is None:
                problem = self._state_problem
            elif not self._current:
                self._current = self.requested_topic
            for topic in list(self._topics.values()):
                if not topic.registered:
                    self._register(topic)
            if self._current not in self._topics:
                self._register(self._subscribe(self._current))
        except (ValueError, TypeError) as error:  # an answer of a shape not foreseen: that call's problem
            self._master_problem = self._odd(f"an odd answer: {error}")
            return
        except Ros1CallError as error:
            if error.unreachable:
                self._master_ok = False
                self._master_problem = self._waiting(error.reason)
            else:
                self._master_problem = self._odd(error.reason)
            return
        self._master_ok = True
        self._master_problem = self._odd(problem) if problem else ""

    def _odd(self, reason: str) -> str:
        return f"the master at {self.environment.master_uri}: {reason} (trying again)"

    def _waiting(self, reason: str) -> str:
        text = f"waiting for master at {self.environment.master_uri}"
        if self.environment.master_defaulted:
            text += " (ROS_MASTER_URI is not set)"
        return f"{text}: {reason}" if reason else text

    def _choose_topic(self, agg_publishers: list[str]) -> None:
        """``/rosout_agg`` while a reachable rosout node publishes it, else ``/rosout``."""
        nodes = frozenset(agg_publishers)
        agg = self._topics.get(ROSOUT_AGG)
        if self._current == ROSOUT_AGG and agg is not None and agg.registered and agg.unreachable():
            self._dead_agg = nodes  # killed, still registered: read the nodes directly meanwhile
        if nodes != self._dead_agg:
            self._dead_agg = frozenset()
        wanted = ROSOUT_AGG if nodes and not self._dead_agg else ROSOUT
        if wanted == self._current:
            return
        old, self._current = self._current, wanted
        if old and old in self._topics:
            assert self._intake is not None
            self._intake.dedupe_for(OVERLAP_S + 2.0)
            self._retiring = (old, time.monotonic() + OVERLAP_S)
            self._delivering_since = None
        self._subscribe(wanted)

    def _subscribe(self, name: str) -> SubscribedTopic:
        topic = self._topics.get(name)
        if topic is None:
            topic = self._topics[name] = SubscribedTopic(name)
            self._topic_names = tuple(self._topics)
        return topic

    def _register(self, topic: SubscribedTopic) -> None:
        publishers = self._master.register_subscriber(topic.name, TYPE, self.slave_uri)
        topic.registered = True
        topic.set_publishers(publishers)

    def _unregister(self, name: str) -> None:
        topic = self._topics.pop(name, None)
        self._topic_names = tuple(self._topics)
        if self._intake is not None:
            self._intake.close_topic(name)
        if topic is not None and topic.registered and self._master_ok:
            try:
                Master(self.environment.master_uri, self.node_name, UNREGISTER_TIMEOUT_S).unregister_subscriber(
                    name, self.slave_uri
                )
            except Ros1CallError:
                pass

    def _retire_if_ready(self) -> None:
        """End the old topic once the new one has delivered messages for ``RELAY_SETTLE_S``
        (or has no publisher to wait for), or its time is up."""
        if self._retiring is None:
            return
        old, deadline = self._retiring
        now = time.monotonic()
        new = self._topics.get(self._current)
        if new is not None and new.connected and self._delivering_since is None and self._delivering(self._current):
            self._delivering_since = now
        settled = self._delivering_since is not None and now - self._delivering_since >= RELAY_SETTLE_S
        nothing_to_wait_for = new is not None and new.registered and not new.publishers
        if settled or nothing_to_wait_for or now >= deadline:
            self._retiring = None
            self._unregister(old)
            # What both topics delivered may still be on its way (a busy machine, a slow
            # rosout node): the check for repeats lasts until well after the old one closed.
            assert self._intake is not None
            self._intake.dedupe_for(OVERLAP_S)

    def _delivering(self, topic: str) -> bool:
        """Whether a connection of ``topic`` has delivered a message."""
        assert self._intake is not None
        return any(c.topic == topic and c.messages for c in self._intake.connections())

    # -- publishers -----------------------------------------------------------------------------

    def _connect_due(self) -> None:
        now = time.monotonic()
        room = connection_room(self._topics.values())
        for topic in self._topics.values():
            for uri in topic.due(now, room):
                assert self._pool is not None
                room -= 1
                self._pool.submit(self._connect, topic.name, uri)

    def _next_retry(self) -> float:
        times = [when for topic in self._topics.values() for when in topic.retry_at.values()]
        return min(times, default=time.monotonic() + 1.0)

    def _connect(self, topic: str, uri: str) -> None:
        """On a pool thread: ask the publisher for a connection and open it."""
        deadline = time.monotonic() + self.call_timeout
        try:
            answer = xmlrpc_call(uri, "requestTopic", self.node_name, topic, [["TCPROS"]], timeout=self.call_timeout)
            if (
                not isinstance(answer, (list, tuple))
                or len(answer) < 3
                or answer[0] != "TCPROS"
                or not isinstance(answer[2], int)
            ):
                raise TcprosError(f"{uri} offers no TCPROS connection: {shown(answer)}")
            sock, header = open_subscription(
                str(answer[1]),
                answer[2],
                caller_id=self.node_name,
                topic=topic,
                msg_type=TYPE,
                md5sum=MD5SUM,
                timeout=max(deadline - time.monotonic(), 0.001),
            )
        except (Ros1CallError, TcprosError, ValueError, TypeError) as error:
            refused = isinstance(error, TcprosError) and error.refused_by_peer
            gone = isinstance(error, Ros1CallError) and error.gone  # a killed node's registration
            self._events.put(("failed", topic, uri, str(error), refused, not gone))
            return
        self._events.put(("connected", topic, uri, sock, header))

    def _on_closed(self, connection: Connection, reason: str) -> None:
        self._events.put(("closed", connection.topic, connection.publisher, reason))

    def _handle(self, event: tuple[Any, ...]) -> None:
        kind = event[0]
        if kind == "update":
            _, name, publishers = event
            topic = self._topics.get(name)
            if topic is not None:
                topic.set_publishers(publishers)
        elif kind == "connected":
            _, name, uri, sock, header = event
            topic = self._topics.get(name)
            if topic is None or self._intake is None or self._stop.is_set():
                sock.close()
                return
            topic.on_connected(uri)
            self._intake.add(Connection(sock, name, uri, header.get("callerid", uri)))
        elif kind == "failed":
            _, name, uri, reason, refused, trouble = event
            topic = self._topics.get(name)
            if topic is not None:
                topic.on_failed(uri, reason, refused, trouble)
        elif kind == "closed":
            _, name, uri, reason = event
            topic = self._topics.get(name)
            if topic is not None:
                topic.on_closed(uri, "" if reason == CLOSED else reason)
        elif kind == "shutdown":
            _, caller, reason = event
            self._ended = f"ROS 1 intake stopped by {caller}" + (f": {reason}" if reason else "")

    # -- status and the end --------------------------------------------------------------------

    def _show(self) -> None:
        topic = self._topics.get(self._current)
        problems = [self._master_problem] if self._master_problem else []
        intake = self._intake
        if topic is not None and topic.refused:
            uri, reason = next(iter(topic.refused.items()))
            problems.append(f"a publisher at {uri} refused {topic.name}: {reason}")
        if intake is not None and intake.last_problem and intake.lost_undecodable:
            problems.append(intake.last_problem)
        if topic is not None and topic.trouble:
            problems.append(topic.trouble_text())
        problems.append(not_read_text(self._topics.values()))
        lost_undecodable = intake.lost_undecodable if intake is not None else 0
        lost_queue = self.queue.dropped
        changes = {
            "topic": self._current,
            "publishers": len(topic.connected) if topic is not None else 0,
            "problem": "; ".join(problem for problem in problems if problem),
            "lost": lost_undecodable + lost_queue,
            "lost_queue": lost_queue,
            "lost_undecodable": lost_undecodable,
            "path": PATH_COMPILED if intake is not None and intake.compiled else PATH,
            "path_note": intake.compiled_note if intake is not None else "",
        }
        if any(self.status.__dict__[key] != value for key, value in changes.items()):
            self._set_status(**changes)

    def _close_all(self) -> None:
        for name in list(self._topics):
            self._unregister(name)
        if self._pool is not None:
            self._pool.shutdown(wait=False, cancel_futures=True)
        if self._intake is not None:
            self._intake.stop()
        if self._server is not None:
            self._server.close()
        # Connections opened by pool threads after the end are closed as they report in.
        while True:
            try:
                event = self._events.get_nowait()
            except queue.Empty:
                break
            if event[0] == "connected":
                event[3].close()
