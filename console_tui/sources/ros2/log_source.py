"""The live log stream: a background thread that takes ``/rosout`` messages in batches.

The thread waits on its subscriptions and then takes every message that is ready, with
no executor in between (rclpy's executors cost about 100 us per callback), and hands
each batch to an ``IntakeQueue``.

QoS: the main subscription is RELIABLE + TRANSIENT_LOCAL with a deep queue, so a
console started late still gets the history each node's rosout publisher keeps. Such a
subscription never matches a publisher whose rosout QoS was made VOLATILE (or
BEST_EFFORT); when the graph shows one, a second, VOLATILE + BEST_EFFORT subscription is
added, and from it only messages of the publishers the first one cannot match are kept
(by publisher GID), so nothing arrives twice.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from ...model.intake_queue import IntakeQueue
from ...model.record import LogRecord
from ..status import SourceStatus
from .runtime import RosRuntime

ROSOUT = "/rosout"
ROSOUT_AGG = "/rosout_agg"
QUEUE_DEPTH = 10_000
WAIT_TIMEOUT_NS = 100_000_000
GRAPH_PERIOD_S = 1.0
AUTO_TOPIC_WAIT_S = 1.0
MAX_BATCH = 20_000


def log_to_record(message: Any, source: str) -> LogRecord:
    """An ``rcl_interfaces/msg/Log`` (or anything with its fields) as a record."""
    stamp = message.stamp
    return LogRecord(
        stamp_ns=stamp.sec * 1_000_000_000 + stamp.nanosec,
        level=message.level,
        node=message.name,
        msg=message.msg,
        file=message.file,
        function=message.function,
        line=message.line,
        source=source,
    )


class LiveLogSource:
    """Reads a log topic in a background thread into an ``IntakeQueue``.

    ``topic=None`` reads ``/rosout_agg`` when something publishes it, else ``/rosout``.
    ``status`` is replaced by the thread as things change; read it from any thread.
    """

    def __init__(self, runtime: RosRuntime, queue: IntakeQueue, topic: str | None = None) -> None:
        self.runtime = runtime
        self.queue = queue
        self.requested_topic = topic
        self.status = SourceStatus(topic=topic or "", path="typed")
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._guard: Any = None

    # -- control, from the UI thread ------------------------------------------------------

    def start(self) -> None:
        self._thread = threading.Thread(target=self._run_guarded, name="console-tui-intake", daemon=True)
        self._thread.start()

    def stop(self, timeout: float = 3.0) -> None:
        self._stop.set()
        guard = self._guard
        if guard is not None:
            try:
                guard.trigger()
            except Exception:
                pass
        if self._thread is not None:
            self._thread.join(timeout)

    # -- the intake thread ------------------------------------------------------------------

    def _set_status(self, **changes: Any) -> None:
        values = {**self.status.__dict__, **changes}
        self.status = SourceStatus(**values)

    def _run_guarded(self) -> None:
        try:
            self._run()
        except Exception as error:  # the app must learn of it, never die of it
            if not self._stop.is_set():
                self._set_status(problem=f"intake stopped: {type(error).__name__}: {error}", running=False)
        else:
            self._set_status(running=False)

    def _run(self) -> None:
        from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
        from rcl_interfaces.msg import Log

        node = self.runtime.create_node("log")
        self._guard = node.create_guard_condition(lambda: None)
        topic = self.requested_topic or self._choose_topic(node)
        reader = _TopicReader(node, Log, topic)
        self._set_status(topic=topic, running=True)
        next_graph_check = 0.0
        wait_set = None
        wait_set_subs: tuple = ()
        while not self._stop.is_set():
            now = time.monotonic()
            if now >= next_graph_check:
                next_graph_check = now + GRAPH_PERIOD_S
                if self.requested_topic is None and reader.topic == ROSOUT and _has_publishers(node, ROSOUT_AGG):
                    reader.close()
                    reader = _TopicReader(node, Log, ROSOUT_AGG)
                reader.refresh_graph()
                self._set_status(topic=reader.topic, publishers=reader.publisher_count)
            subs = reader.handles()
            if wait_set is None or subs != wait_set_subs:
                wait_set = _rclpy.WaitSet(len(subs), 1, 0, 0, 0, 0, self.runtime.context.handle)
                wait_set_subs = subs
            wait_set.clear_entities()
            for handle in subs:
                wait_set.add_subscription(handle)
            wait_set.add_guard_condition(self._guard.handle)
            wait_set.wait(WAIT_TIMEOUT_NS)
            if self._stop.is_set():
                break
            batch = reader.take_all(MAX_BATCH)
            if batch:
                self.queue.put(batch)
        reader.close()

    def _choose_topic(self, node: Any) -> str:
        deadline = time.monotonic() + AUTO_TOPIC_WAIT_S
        while time.monotonic() < deadline and not self._stop.is_set():
            if _has_publishers(node, ROSOUT_AGG):
                return ROSOUT_AGG
            time.sleep(0.05)
        return ROSOUT


def _has_publishers(node: Any, topic: str) -> bool:
    return node.count_publishers(topic) > 0


def _gid_bytes(gid: Any) -> bytes:
    data = gid.get("data", b"") if isinstance(gid, dict) else gid
    return bytes(data)


class _TopicReader:
    """The subscriptions on one topic, and which publishers each of them stands for."""

    def __init__(self, node: Any, msg_type: Any, topic: str, convert: Callable[[Any, str], LogRecord] = log_to_record) -> None:
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        self.node = node
        self.msg_type = msg_type
        self.topic = topic
        self.convert = convert
        self.publisher_count = 0
        self._volatile_qos = QoSProfile(
            history=HistoryPolicy.KEEP_LAST,
            depth=QUEUE_DEPTH,
            reliability=ReliabilityPolicy.BEST_EFFORT,
            durability=DurabilityPolicy.VOLATILE,
        )
        self.main = node.create_subscription(
            msg_type,
            topic,
            _ignore,
            QoSProfile(
                history=HistoryPolicy.KEEP_LAST,
                depth=QUEUE_DEPTH,
                reliability=ReliabilityPolicy.RELIABLE,
                durability=DurabilityPolicy.TRANSIENT_LOCAL,
            ),
        )
        self.extra: Any = None
        #: GIDs of the publishers only the extra (VOLATILE) subscription matches.
        self._uncovered: set[bytes] = set()
        self._covered: set[bytes] = set()

    def handles(self) -> tuple:
        if self.extra is None:
            return (self.main.handle,)
        return (self.main.handle, self.extra.handle)

    def refresh_graph(self) -> None:
        from rclpy.qos import DurabilityPolicy, ReliabilityPolicy

        covered: set[bytes] = set()
        uncovered: set[bytes] = set()
        infos = self.node.get_publishers_info_by_topic(self.topic)
        for info in infos:
            qos = info.qos_profile
            matches_main = (
                qos.durability == DurabilityPolicy.TRANSIENT_LOCAL
                and qos.reliability == ReliabilityPolicy.RELIABLE
            )
            (covered if matches_main else uncovered).add(_gid_bytes(info.endpoint_gid))
        self.publisher_count = len(infos)
        self._covered, self._uncovered = covered, uncovered
        if uncovered and self.extra is None:
            self.extra = self.node.create_subscription(self.msg_type, self.topic, _ignore, self._volatile_qos)

    def take_all(self, limit: int) -> list[LogRecord]:
        batch: list[LogRecord] = []
        convert, topic = self.convert, self.topic
        take = self.main.handle.take_message
        msg_type = self.msg_type
        while len(batch) < limit:
            taken = take(msg_type, False)
            if taken is None:
                break
            batch.append(convert(taken[0], topic))
        if self.extra is not None:
            take = self.extra.handle.take_message
            refreshed = False
            while len(batch) < limit:
                taken = take(msg_type, False)
                if taken is None:
                    break
                gid = _gid_bytes(taken[1].get("publisher_gid") or b"")
                if gid not in self._uncovered and gid not in self._covered and not refreshed:
                    self.refresh_graph()  # a publisher newer than our last look
                    refreshed = True
                if gid in self._covered:
                    continue  # the main subscription has this one already
                batch.append(convert(taken[0], topic))
        return batch

    def close(self) -> None:
        for sub in (self.main, self.extra):
            if sub is not None:
                try:
                    self.node.destroy_subscription(sub)
                except Exception:
                    pass
        self.extra = None


def _ignore(_message: Any) -> None:
    """Subscriptions need a callback; messages are taken by the intake loop instead."""
