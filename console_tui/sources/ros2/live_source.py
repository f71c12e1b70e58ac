"""The live log stream: a background thread that takes ``/rosout`` messages in batches.

The thread waits on its subscriptions (``TopicReader``, in ``topic_reader.py``) and then
takes every message that is ready, with no executor in between, and hands each batch to
an ``IntakeQueue``. Messages are read by the direct CDR decoder, path ``raw+cdr``, or
typed by rclpy (``typed``); ``SourceStatus.path`` says which is in use.

When only a trickle arrives the loop pauses after each batch (``coalesce.Coalescer``), so
that a turn of the loop pays for more than one message. ``stop()`` returns within tens of ms.
Why no executor: docs/decisions/0003-take-without-executor.md.

Loss is counted, never silent (``loss_counts.py``): the middleware's message-lost events
and sequence gaps, batches the full ``IntakeQueue`` refused, and undecodable messages add
up to ``SourceStatus.lost``. Fast DDS keeps at most ``topic_reader.QUEUE_DEPTH`` unread
messages per subscription (with ``fastdds_reader_profile.xml``; about 5,000 without),
whatever the depth asked for: what arrives while this thread cannot run for longer than
that is lost, and reported as such.

Topic: ``topic=None`` reads ``/rosout_agg`` when something publishes it, else ``/rosout``
(``TopicChoice``, in ``topic_choice.py``): nothing arrives twice when it switches.
"""

from __future__ import annotations

import threading
import time
from typing import Any

from ...model.inert_text import plural
from ...model.store.intake_queue import IntakeQueue
from ...ros.ros2.runtime import RosRuntime
from ...system.thread_names import os_named
from ..coalesce import Coalescer
from ..log_topics import ROSOUT, ROSOUT_AGG
from ..status import SourceStatus
from .loss_counts import LossCounts
from .topic_choice import START_GRAPH_PERIOD_S, TopicChoice
from .topic_reader import PATH_RAW, PATH_TYPED, TopicReader

WAIT_TIMEOUT_NS = 100_000_000
GRAPH_PERIOD_S = 1.0
MAX_BATCH = 2_000


class LiveLogSource:
    """Reads a log topic in a background thread into an ``IntakeQueue``.

    ``topic=None`` reads ``/rosout_agg`` when something publishes it, else ``/rosout``.
    ``raw=False`` takes typed messages (the slower path rclpy always has).
    ``min_level`` (``tail --level``) asks the middleware to drop what is below it
    (``level_filter.py``; the intake process drops what it still sends).
    ``status`` is replaced by the thread as things change; read it from any thread.
    """

    def __init__(
        self, runtime: RosRuntime, queue: IntakeQueue, topic: str | None = None, *, raw: bool = True, min_level: int = 0
    ) -> None:
        self.runtime = runtime
        self.queue = queue
        self.requested_topic = topic
        self.raw = raw
        self.min_level = min_level
        self.status = SourceStatus(topic=topic or "", path=PATH_RAW if raw else PATH_TYPED, min_level=min_level)
        self.counts = LossCounts()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._guard: Any = None

    # -- control, from the thread that owns the source ---------------------------------------

    def start(self) -> None:
        self._thread = threading.Thread(target=os_named(self._run_guarded), name="console-tui-intake", daemon=True)
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

    def _loss_fields(self, reader: TopicReader) -> dict[str, Any]:
        counts = self.counts
        lost_queue = self.queue.dropped
        fields: dict[str, Any] = {
            "path": reader.path,
            "path_note": reader.path_note,
            "lost": counts.lost_in_middleware + lost_queue + counts.lost_undecodable,
            "lost_qos": counts.lost_in_middleware,
            "lost_queue": lost_queue,
            "lost_undecodable": counts.lost_undecodable,
            "decoded_by_rclpy": counts.decoded_by_rclpy,
            "incompatible": counts.incompatible,
            "level_filter_note": reader.filter_note,
        }
        if counts.incompatible:
            fields["problem"] = (
                f"{plural(counts.incompatible, 'publisher')} on {reader.topic} with a QoS no subscription can match"
                f" ({counts.last_policy or 'unknown policy'}): their messages are not received"
            )
        return fields

    def _run_guarded(self) -> None:
        try:
            self._run()
        except Exception as error:  # the app must learn of it, never die of it
            if not self._stop.is_set():
                self._set_status(problem=f"intake stopped: {type(error).__name__}: {error}", running=False)
        else:
            self._set_status(running=False)

    def _run(self) -> None:
        from rcl_interfaces.msg import Log
        from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy

        node = self.runtime.create_node("log")
        self._guard = node.create_guard_condition(lambda: None)
        choice = TopicChoice(time.monotonic()) if self.requested_topic is None else None
        topic = self.requested_topic or ROSOUT
        reader = TopicReader(node, Log, topic, self.counts, raw=self.raw, min_level=self.min_level)
        self._set_status(topic=topic, running=True, **self._loss_fields(reader))
        next_graph_check = 0.0
        wait_set = None
        wait_set_entities: tuple = ()
        shown = None
        coalescer = Coalescer()
        while not self._stop.is_set():
            now = time.monotonic()
            if (
                choice is not None
                and reader.topic == ROSOUT
                and now >= next_graph_check
                and _has_publishers(node, ROSOUT_AGG)
            ):
                reader.close()
                reader = TopicReader(node, Log, ROSOUT_AGG, self.counts, raw=self.raw, min_level=self.min_level)
                choice.switched(now)
                next_graph_check = 0.0
            if now >= next_graph_check or reader.graph_changed:
                discovering = choice is not None and choice.discovering(now)
                next_graph_check = now + (START_GRAPH_PERIOD_S if discovering else GRAPH_PERIOD_S)
                reader.refresh_graph()
                self._set_status(topic=reader.topic, publishers=reader.publisher_count)
            subs, events = reader.handles(), reader.event_handlers()
            if wait_set is None or (subs, events) != wait_set_entities:
                context = self.runtime.context.handle
                assert context is not None  # the runtime's context lives as long as the source
                wait_set = _rclpy.WaitSet(len(subs), 1, 0, 0, 0, len(events), context)
                wait_set_entities = (subs, events)
            wait_set.clear_entities()
            for handle in subs:
                wait_set.add_subscription(handle)
            wait_set.add_guard_condition(self._guard.handle)
            for handler in events:
                handler.add_to_wait_set(wait_set)
            wait_set.wait(WAIT_TIMEOUT_NS)
            if self._stop.is_set():
                break
            if events:
                reader.handle_events(wait_set)
            batch = reader.take_all(MAX_BATCH)
            taken = len(batch)
            if reader.graph_changed:  # a new publisher's history: the app learns of it first
                reader.refresh_graph()
                self._set_status(publishers=reader.publisher_count)
            if choice is not None:
                batch = choice.filter(batch, reader.topic, time.monotonic())
            if batch:
                self.queue.put(batch)
            pause = coalescer.after(taken)
            if pause:
                self._stop.wait(pause)
            loss = (
                self.queue.dropped,
                reader.path,
                self.counts.lost_in_middleware,
                self.counts.lost_undecodable,
                self.counts.decoded_by_rclpy,
                self.counts.incompatible,
            )
            if loss != shown:
                shown = loss
                self._set_status(**self._loss_fields(reader))
        reader.close()


def _has_publishers(node: Any, topic: str) -> bool:
    count: int = node.count_publishers(topic)
    return count > 0
