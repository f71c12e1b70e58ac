"""The live log stream: a background thread that takes ``/rosout`` messages in batches.

The thread waits on its subscriptions and then takes every message that is ready, with
no executor in between, and hands each batch to an ``IntakeQueue``. Messages are taken
serialized and read by the direct CDR decoder (``cdr.LogDecoder``), path ``raw+cdr``; a
message the decoder refuses goes through rclpy's deserializer instead, and an rclpy
that cannot take serialized messages gets the typed path (``typed``).
``SourceStatus.path`` says which is in use.

Measured with benchmarks/intake.py (2 cores, Fast DDS): this loop needs less CPU per
message than an EventsExecutor feeding the same decoder (which also lost a quarter of
20k messages/s where this loop lost none), and about as much as a raw EventsExecutor
subscription that only counts; a typed ``rclpy.spin`` needs more than ten times as much.
When only a trickle arrives the loop pauses ``COALESCE_S`` after each batch, so that a
turn of the loop pays for more than one message. ``stop()`` returns within tens of ms.

Loss is counted, never silent: the middleware's message-lost events, batches the full
``IntakeQueue`` refused, and undecodable messages add up to ``SourceStatus.lost``.
Fast DDS keeps at most about 6,000 unread messages per subscription, whatever the
depth asked for: what arrives while this thread cannot run for longer than that is
lost, and reported as such.

Topic: ``topic=None`` reads ``/rosout_agg`` when something publishes it (a rosout node,
such as ``console-tui rosout``, keeps a deep history there), else ``/rosout`` (see
``_TopicChoice``): nothing arrives twice when it switches, and at start, when discovery
finds the aggregator while it holds ``/rosout`` back, the history comes in time order.

QoS: the main subscription is RELIABLE + TRANSIENT_LOCAL with a deep queue, so a
console started late still gets the history each node's rosout publisher keeps. Such a
subscription never matches a publisher whose rosout QoS was made VOLATILE (or
BEST_EFFORT); when the graph shows one, a second, VOLATILE + BEST_EFFORT subscription is
added, and from it only messages of the publishers the first one cannot match are kept
(by publisher GID; where rclpy's message info has no GID, as in Jazzy, by the logger name
of the publisher's node), so nothing arrives twice. When the main subscription reports an
incompatible publisher, the graph is looked at again at once, so that second
subscription starts without waiting for the next periodic look.
"""

from __future__ import annotations

import threading
import time
from typing import Any

from ...model.formats.ros2_log_msg import CdrError, LogDecoder
from ...model.intake_queue import IntakeQueue
from ...model.logger_levels import node_logger_name
from ...model.record import LogRecord
from ...model.text import plural
from ..log_message import log_to_record
from ..log_topics import ROSOUT, ROSOUT_AGG
from ..status import SourceStatus
from .runtime import RosRuntime

QUEUE_DEPTH = 50_000  # Fast DDS holds this many only with fastdds_reader_profile.xml (else 5,000)
WAIT_TIMEOUT_NS = 100_000_000
GRAPH_PERIOD_S = 1.0
UNKNOWN_PUBLISHER_REFRESH_S = 0.2
#: At start, ``/rosout`` messages are held back while ``/rosout_agg`` may still be
#: discovered: at least ``AUTO_TOPIC_MIN_S``, until the ``/rosout`` publishers found have
#: not changed for ``AUTO_TOPIC_SETTLED_S``, at most ``AUTO_TOPIC_MAX_S`` (discovery took
#: 1-2 s on the development machine, longer when it was busy).
AUTO_TOPIC_MIN_S = 1.0
AUTO_TOPIC_SETTLED_S = 1.0
AUTO_TOPIC_MAX_S = 5.0
#: After a late switch to ``/rosout_agg``: how long its history is checked against what
#: ``/rosout`` already gave.
SWITCH_DEDUPE_S = 30.0
MAX_BATCH = 2_000
COALESCE_BELOW = 64
COALESCE_S = 0.002
PATH_RAW = "raw+cdr"
PATH_TYPED = "typed"


class LossCounts:
    """What the intake thread counts as it goes; turned into ``SourceStatus`` fields.

    Loss in the middleware is counted twice over, and the larger count shown: by the
    middleware's message-lost events (``lost_qos``), and by the gaps in each publisher's
    sequence numbers (``lost_gaps``, see ``SequenceGaps``). Each misses what the other
    sees: Fast DDS reports nothing for messages its reader history overwrote (KEEP_LAST),
    nor, it seems, when the publisher left before telling it; gaps need a publisher GID in
    the message info (Jazzy's rclpy gives none) and the next message from that publisher.
    """

    __slots__ = ("decoded_by_rclpy", "incompatible", "last_policy", "lost_gaps", "lost_qos", "lost_undecodable")

    def __init__(self) -> None:
        self.lost_qos = 0
        self.lost_gaps = 0
        self.lost_undecodable = 0
        self.decoded_by_rclpy = 0
        self.incompatible = 0
        self.last_policy = ""

    @property
    def lost_in_middleware(self) -> int:
        return max(self.lost_qos, self.lost_gaps)


class SequenceGaps:
    """Messages lost as the gaps in each publisher's sequence numbers show.

    A publisher numbers what it sends 1, 2, 3...; a subscription that got 7 then 10 from
    the same publisher (by GID) lost 2. The first number seen from a publisher starts its
    count (what it sent before we joined is not ours to miss)."""

    __slots__ = ("_last", "counts")

    def __init__(self, counts: LossCounts) -> None:
        self.counts = counts
        self._last: dict[bytes, int] = {}

    def see(self, info: dict) -> None:
        gid = info.get("publisher_gid")
        number = info.get("publication_sequence_number")
        if not gid or not number:
            return
        key = gid.get("data", b"") if isinstance(gid, dict) else gid
        last = self._last.get(key)
        if last is None or number > last:
            if last is not None and number > last + 1:
                self.counts.lost_gaps += number - last - 1
            self._last[key] = number


class LiveLogSource:
    """Reads a log topic in a background thread into an ``IntakeQueue``.

    ``topic=None`` reads ``/rosout_agg`` when something publishes it, else ``/rosout``.
    ``raw=False`` takes typed messages (the slower path rclpy always has).
    ``status`` is replaced by the thread as things change; read it from any thread.
    """

    def __init__(self, runtime: RosRuntime, queue: IntakeQueue, topic: str | None = None, *, raw: bool = True) -> None:
        self.runtime = runtime
        self.queue = queue
        self.requested_topic = topic
        self.raw = raw
        self.status = SourceStatus(topic=topic or "", path=PATH_RAW if raw else PATH_TYPED)
        self.counts = LossCounts()
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

    def _loss_fields(self, reader: _TopicReader) -> dict[str, Any]:
        counts = self.counts
        lost_queue = self.queue.dropped
        fields: dict[str, Any] = {
            "path": reader.path,
            "lost": counts.lost_in_middleware + lost_queue + counts.lost_undecodable,
            "lost_qos": counts.lost_in_middleware,
            "lost_queue": lost_queue,
            "lost_undecodable": counts.lost_undecodable,
            "decoded_by_rclpy": counts.decoded_by_rclpy,
            "incompatible": counts.incompatible,
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
        choice = _TopicChoice(time.monotonic()) if self.requested_topic is None else None
        topic = self.requested_topic or ROSOUT
        reader = _TopicReader(node, Log, topic, self.counts, raw=self.raw)
        self._set_status(topic=topic, running=True, **self._loss_fields(reader))
        next_graph_check = 0.0
        wait_set = None
        wait_set_entities: tuple = ()
        shown = None
        while not self._stop.is_set():
            now = time.monotonic()
            if (
                choice is not None
                and reader.topic == ROSOUT
                and (now >= next_graph_check or choice.holding(now))
                and _has_publishers(node, ROSOUT_AGG)
            ):
                reader.close()
                reader = _TopicReader(node, Log, ROSOUT_AGG, self.counts, raw=self.raw)
                choice.switched(now)
                next_graph_check = 0.0
            holding = choice is not None and choice.holding(now)
            if now >= next_graph_check or reader.graph_changed or holding:
                next_graph_check = now + GRAPH_PERIOD_S
                reader.refresh_graph()
                if holding and choice is not None:
                    choice.publishers(reader.publisher_count, now)
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
            if choice is not None:
                batch = choice.filter(batch, reader.topic, time.monotonic())
            if batch:
                self.queue.put(batch)
            if len(batch) < COALESCE_BELOW:
                # A trickle: let a few milliseconds of messages gather, so that each turn
                # of this loop (a wait set rebuilt and waited on) pays for more of them.
                self._stop.wait(COALESCE_S)
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


class _TopicChoice:
    """``/rosout_agg`` when something publishes it, else ``/rosout``, never a message twice.

    - At start, ``/rosout`` messages are held back while discovery may still find a
      ``/rosout_agg`` publisher (see ``AUTO_TOPIC_MIN_S``). When one shows up, the held
      messages are dropped (its history has them, and older ones) and the stream starts
      from ``/rosout_agg``, in time order. Otherwise they go out when the time is up.
    - When one shows up later, its history is delivered without what ``/rosout`` already
      gave: for each logger name, the messages outside the span of time ``/rosout`` covered
      for it. Those older than that span (``/rosout`` keeps only its last 10 s) come after
      newer ones then, since records are shown in arrival order, but none is lost.
    """

    def __init__(self, start: float) -> None:
        self.start = start
        self.deadline = start + AUTO_TOPIC_MAX_S
        self.held: list[LogRecord] = []
        #: Per logger name, the oldest and newest stamps ``/rosout`` gave.
        self.oldest: dict[str, int] = {}
        self.newest: dict[str, int] = {}
        self.dedupe_until = 0.0
        self._publishers = 0
        self._changed_at = start

    def publishers(self, count: int, now: float) -> None:
        """The number of ``/rosout`` publishers found so far; once it has settled, stop holding."""
        if count != self._publishers:
            self._publishers, self._changed_at = count, now
        elif count and now - self._changed_at >= AUTO_TOPIC_SETTLED_S and now - self.start >= AUTO_TOPIC_MIN_S:
            self.deadline = min(self.deadline, now)

    def holding(self, now: float) -> bool:
        return now < self.deadline

    def switched(self, now: float) -> None:
        if self.holding(now):
            self.held.clear()
            self.oldest.clear()
            self.newest.clear()
        else:
            self.dedupe_until = now + SWITCH_DEDUPE_S
        self.deadline = 0.0

    def filter(self, batch: list[LogRecord], topic: str, now: float) -> list[LogRecord]:
        if topic == ROSOUT:
            oldest, newest = self.oldest, self.newest
            for record in batch:
                oldest.setdefault(record.node, record.stamp_ns)
                newest[record.node] = record.stamp_ns
            if self.holding(now):
                self.held.extend(batch)
                return []
            if self.held:
                batch, self.held = self.held + batch, []
            return batch
        if now < self.dedupe_until:
            oldest, newest = self.oldest, self.newest
            return [
                r for r in batch if r.node not in newest or not oldest[r.node] <= r.stamp_ns <= newest[r.node]
            ]
        if self.newest:
            self.oldest, self.newest = {}, {}
        return batch


def _has_publishers(node: Any, topic: str) -> bool:
    count: int = node.count_publishers(topic)
    return count > 0


def _gid_bytes(gid: Any) -> bytes:
    data = gid.get("data", b"") if isinstance(gid, dict) else gid
    return bytes(data)


def _subscription_event_callbacks() -> Any:
    try:
        from rclpy.event_handler import SubscriptionEventCallbacks
    except ImportError:  # Humble
        from rclpy.qos_event import SubscriptionEventCallbacks
    return SubscriptionEventCallbacks


def _policy_name(info: Any) -> str:
    """The QoS policy an incompatible-QoS event names last, for example ``durability``."""
    kind = getattr(info, "last_policy_kind", None)
    return str(getattr(kind, "name", kind or "")).lower()


class _TopicReader:
    """The subscriptions on one topic, and which publishers each of them stands for."""

    def __init__(self, node: Any, msg_type: Any, topic: str, counts: LossCounts, *, raw: bool = True) -> None:
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        self.node = node
        self.msg_type = msg_type
        self.topic = topic
        self.counts = counts
        self.decoder = LogDecoder() if raw else None
        self.publisher_count = 0
        #: Set by an incompatible-QoS event on the main subscription: look at the graph now.
        self.graph_changed = False
        self._volatile_qos = QoSProfile(
            history=HistoryPolicy.KEEP_LAST,
            depth=QUEUE_DEPTH,
            reliability=ReliabilityPolicy.BEST_EFFORT,
            durability=DurabilityPolicy.VOLATILE,
        )
        self.main = self._subscribe(
            QoSProfile(
                history=HistoryPolicy.KEEP_LAST,
                depth=QUEUE_DEPTH,
                reliability=ReliabilityPolicy.RELIABLE,
                durability=DurabilityPolicy.TRANSIENT_LOCAL,
            ),
            main=True,
        )
        self.extra: Any = None
        #: Per subscription: the sequence numbers seen from each publisher.
        self._sequences: dict[int, SequenceGaps] = {}
        #: GIDs of the publishers only the extra (VOLATILE) subscription matches.
        self._uncovered: set[bytes] = set()
        self._covered: set[bytes] = set()
        #: The same by their nodes' logger names, for an rclpy whose message info has no
        #: publisher GID (Jazzy): ``{logger name: covered}``.
        self._node_covered: dict[str, bool] = {}
        #: This rclpy's message info has no publisher GID.
        self._gidless = False
        self._unknown_refreshed_at = 0.0

    @property
    def path(self) -> str:
        return PATH_RAW if self.decoder is not None else PATH_TYPED

    def _subscribe(self, qos: Any, *, main: bool) -> Any:
        """A subscription with loss and incompatibility events, as far as this rclpy and RMW have them."""
        callbacks = _subscription_event_callbacks()
        lost = self._on_message_lost_main if main else self._on_message_lost_extra
        incompatible = self._on_incompatible_main if main else self._on_incompatible_extra
        attempts: list[dict[str, Any]] = []
        try:
            attempts.append(
                {
                    "event_callbacks": callbacks(
                        message_lost=lost, incompatible_qos=incompatible, use_default_callbacks=False
                    )
                }
            )
            attempts.append({"event_callbacks": callbacks(incompatible_qos=incompatible, use_default_callbacks=False)})
        except TypeError:  # an older SubscriptionEventCallbacks
            pass
        attempts.append({})
        for number, options in enumerate(attempts):
            try:
                return self.node.create_subscription(self.msg_type, self.topic, _ignore, qos, **options)
            except Exception:  # the RMW lacks one of these events
                if number == len(attempts) - 1:
                    raise
        raise AssertionError("unreachable")

    def _on_message_lost_main(self, info: Any) -> None:
        self.counts.lost_qos += int(info.total_count_change)

    def _on_message_lost_extra(self, info: Any) -> None:
        # The extra subscription also hears publishers the main one covers; its losses
        # are only counted while it stands for every publisher it hears.
        if not self._covered:
            self.counts.lost_qos += int(info.total_count_change)

    def _on_incompatible_main(self, _info: Any) -> None:
        self.graph_changed = True

    def _on_incompatible_extra(self, info: Any) -> None:
        self.counts.incompatible += int(info.total_count_change)
        self.counts.last_policy = _policy_name(info)

    def handles(self) -> tuple:
        if self.extra is None:
            return (self.main.handle,)
        return (self.main.handle, self.extra.handle)

    def event_handlers(self) -> tuple:
        handlers = tuple(self.main.event_handlers)
        if self.extra is not None:
            handlers += tuple(self.extra.event_handlers)
        return handlers

    def handle_events(self, wait_set: Any) -> None:
        for handler in self.event_handlers():
            if handler.is_ready(wait_set):
                info = handler.take_data()
                if info is not None:
                    handler.callback(info)

    def refresh_graph(self) -> None:
        from rclpy.qos import DurabilityPolicy, ReliabilityPolicy

        self.graph_changed = False
        covered: set[bytes] = set()
        uncovered: set[bytes] = set()
        node_covered: dict[str, bool] = {}
        infos = self.node.get_publishers_info_by_topic(self.topic)
        for info in infos:
            qos = info.qos_profile
            matches_main = (
                qos.durability == DurabilityPolicy.TRANSIENT_LOCAL and qos.reliability == ReliabilityPolicy.RELIABLE
            )
            (covered if matches_main else uncovered).add(_gid_bytes(info.endpoint_gid))
            node_covered[node_logger_name(info.node_namespace, info.node_name)] = matches_main
        self.publisher_count = len(infos)
        self._covered, self._uncovered, self._node_covered = covered, uncovered, node_covered
        if uncovered and self.extra is None:
            self.extra = self._subscribe(self._volatile_qos, main=False)

    def _read_refused(self, message: bytes, _error: CdrError) -> LogRecord | None:
        """A message the direct decoder refused, read by rclpy; ``None`` if it cannot either."""
        try:
            from rclpy.serialization import deserialize_message

            record = log_to_record(deserialize_message(message, self.msg_type), self.topic)
        except Exception:
            self.counts.lost_undecodable += 1
            return None
        self.counts.decoded_by_rclpy += 1
        return record

    def _keep_from_extra(self, info: dict) -> bool:
        """Whether a message the extra subscription took is one only it receives (by its
        publisher's GID; kept for ``_keep_record_from_extra`` when the info has none)."""
        if "publisher_gid" not in info:
            self._gidless = True
            return True
        gid = _gid_bytes(info.get("publisher_gid") or b"")
        if gid not in self._uncovered and gid not in self._covered:
            self._refresh_for_unknown()
        return gid not in self._covered

    def _keep_record_from_extra(self, record: LogRecord) -> bool:
        """Without publisher GIDs: whether the record's logger belongs to a node only the
        extra subscription matches (the node whose logger name is the longest prefix of it)."""
        owner = self._owner(record.node)
        if owner is None:
            self._refresh_for_unknown()
            owner = self._owner(record.node)
        return owner is None or not self._node_covered[owner]

    def _owner(self, logger: str) -> str | None:
        while True:
            if logger in self._node_covered:
                return logger
            if "." not in logger:
                return None
            logger = logger.rpartition(".")[0]

    def _refresh_for_unknown(self) -> None:
        now = time.monotonic()
        if now - self._unknown_refreshed_at >= UNKNOWN_PUBLISHER_REFRESH_S:
            self._unknown_refreshed_at = now
            self.refresh_graph()  # a publisher newer than our last look

    def take_all(self, limit: int) -> list[LogRecord]:
        """Every message waiting (up to ``limit``), as records, oldest first per subscription."""
        batch: list[LogRecord] = []
        taken = self._take_into(batch, self.main, limit, None)
        if self.extra is not None and taken < limit:
            extra: list[LogRecord] = []
            self._take_into(extra, self.extra, limit - taken, self._keep_from_extra)
            if extra and self._covered and self._gidless:
                extra = [record for record in extra if self._keep_record_from_extra(record)]
            batch.extend(extra)
        return batch

    def _take_into(self, batch: list[LogRecord], subscription: Any, limit: int, keep: Any) -> int:
        """Take up to ``limit`` messages into ``batch`` (those ``keep(info)`` accepts); how many taken.

        The hot loop of the app: messages are taken first, then decoded all in one call.
        """
        take, msg_type, decoder = subscription.handle.take_message, self.msg_type, self.decoder
        raw = decoder is not None
        messages: list[Any] = []
        append = messages.append
        # (Not on the typed path: a message rclpy cannot deserialize is counted as such.)
        see = self._gaps(subscription).see if raw else _ignore
        count = 0
        while count < limit:
            try:
                taken = take(msg_type, raw)
            except Exception as error:
                if decoder is None:  # a message rclpy took but could not deserialize: it is gone
                    self.counts.lost_undecodable += 1
                    count += 1
                    continue
                if not isinstance(error, TypeError):
                    raise
                batch.extend(decoder.decode_many(messages, self.topic, self._read_refused))
                self.decoder = None  # an rclpy that cannot take serialized messages
                return count + self._take_into(batch, subscription, limit - count, keep)
            if taken is None:
                break
            count += 1
            info = taken[1]
            if keep is None or keep(info):
                append(taken[0])
                see(info)
        if decoder is not None:
            batch.extend(decoder.decode_many(messages, self.topic, self._read_refused))
        else:
            topic = self.topic
            batch.extend([log_to_record(message, topic) for message in messages])
        return count

    def _gaps(self, subscription: Any) -> SequenceGaps:
        gaps = self._sequences.get(id(subscription))
        if gaps is None:
            gaps = self._sequences[id(subscription)] = SequenceGaps(self.counts)
        return gaps

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
