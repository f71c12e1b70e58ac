"""The subscriptions of one log topic: what the live source's loop takes its messages from.

QoS: the main subscription is RELIABLE + TRANSIENT_LOCAL with a deep queue, so a
console started late still gets the history each node's rosout publisher keeps. Such a
subscription never matches a publisher whose rosout QoS was made VOLATILE (or
BEST_EFFORT); when the graph shows one, a second, VOLATILE + BEST_EFFORT subscription is
added, and from it only messages of the publishers the first one cannot match are kept
(by publisher GID; where there is none, as with rclpy's take on Jazzy, whose message info
lacks it, by the logger name of the publisher's node), so nothing arrives twice. When the
main subscription reports an incompatible publisher, the graph is looked at again at once,
so that second subscription starts without waiting for the next periodic look.

Messages are taken serialized and read by the direct CDR decoder (``LogDecoder``), path
``raw+cdr``, or ``c+cdr`` where the take loop runs in C (``compiled_take.py``), which
gives the publisher's GID with each message on every distribution; a message the decoder
refuses goes through rclpy's deserializer instead, and an rclpy that cannot take
serialized messages gets the typed path (``typed``).

With a lowest severity (``min_level``, ``tail --level``) each subscription asks the
middleware for a content filter (``level_filter.py``); ``filter_note`` says why one did not
get it ("" when all did, or none was asked for).
"""

from __future__ import annotations

import itertools
import time
from typing import Any

from ...model.formats.ros2_log_msg import CdrError, LogDecoder
from ...model.loggers.logger_levels import node_logger_name
from ...model.store.record import LogRecord
from ...model.store.record_batch import RecordColumns
from ..status import PATH_NOTE_BUILDING
from . import compiled_take
from .level_filter import filter_below
from .log_message import log_to_record
from .loss_counts import LossCounts, SequenceGaps

QUEUE_DEPTH = 50_000  # Fast DDS holds this many only with fastdds_reader_profile.xml (else 5,000)
UNKNOWN_PUBLISHER_REFRESH_S = 0.2
PATH_RAW = "raw+cdr"
PATH_COMPILED = "c+cdr"
PATH_TYPED = "typed"


def gid_bytes(gid: Any) -> bytes:
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


class TopicReader:
    """The subscriptions on one topic, and which publishers each of them stands for."""

    def __init__(
        self, node: Any, msg_type: Any, topic: str, counts: LossCounts, *, raw: bool = True, min_level: int = 0
    ) -> None:
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        self.node = node
        #: The lowest severity asked for (0: all), and why the middleware does not filter it ("": it does).
        self.min_level = min_level
        self.filter_note = ""
        self.msg_type = msg_type
        self.topic = topic
        self.counts = counts
        self.decoder = LogDecoder() if raw else None
        #: The take loop in C (``None``: rclpy's take, also while it is being built), and
        #: why not when it is missing (or how it was built).
        self.compiled: compiled_take.TakeFunction | None = None
        self.compiled_problem = ""
        self._compiled_pending = raw
        if raw:
            compiled_take.start_loading()
            self._adopt_compiled()
        self.publisher_count = 0
        #: Set by an incompatible-QoS event on the main subscription, and by the first
        #: messages of a publisher (its history): look at the graph now.
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

    def _adopt_compiled(self) -> None:
        """Take through the loop in C from the moment its build is done."""
        done = compiled_take.loaded_now()
        if done is not None:
            self._compiled_pending = False
            self.compiled, self.compiled_problem = done

    @property
    def path(self) -> str:
        if self.decoder is None:
            return PATH_TYPED
        return PATH_COMPILED if self.compiled is not None else PATH_RAW

    @property
    def path_note(self) -> str:
        """Why the take loop in C is not used (or how it was built), or "" (the path is ``typed``)."""
        if self._compiled_pending:
            return PATH_NOTE_BUILDING
        return self.compiled_problem if self.decoder is not None else ""

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
                subscription = self.node.create_subscription(self.msg_type, self.topic, _ignore, qos, **options)
            except Exception:  # the RMW lacks one of these events
                if number == len(attempts) - 1:
                    raise
                continue
            if self.min_level:
                note = filter_below(subscription, self.min_level)
                self.filter_note = self.filter_note or note
                if not note:  # the writers filter: their sequence numbers have gaps that lose nothing
                    self.counts.filtered = True
            return subscription
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
            (covered if matches_main else uncovered).add(gid_bytes(info.endpoint_gid))
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
        publisher's GID; kept for ``_keep_node_from_extra`` when the info has none)."""
        if "publisher_gid" not in info:
            self._gidless = True
            return True
        gid = gid_bytes(info.get("publisher_gid") or b"")
        if gid not in self._uncovered and gid not in self._covered:
            self._refresh_for_unknown()
        return gid not in self._covered

    def _keep_node_from_extra(self, logger: str) -> bool:
        """Without publisher GIDs: whether a record of this logger belongs to a node only the
        extra subscription matches (the node whose logger name is the longest prefix of it)."""
        owner = self._owner(logger)
        if owner is None:
            self._refresh_for_unknown()
            owner = self._owner(logger)
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

    def take_all(self, limit: int) -> RecordColumns:
        """Every message waiting (up to ``limit``), as records in columns, oldest first per subscription."""
        if self._compiled_pending:
            self._adopt_compiled()
        parts: list[RecordColumns] = []
        publishers_seen = self._gaps(self.main).last_seen
        known = len(publishers_seen)
        taken = self._take_into(parts, self.main, limit, None)
        if len(publishers_seen) > known:
            self.graph_changed = True
        if self.extra is not None and taken < limit:
            extra: list[RecordColumns] = []
            self._take_into(extra, self.extra, limit - taken, self._keep_from_extra)
            if extra and self._covered and self._gidless:
                from_extra = RecordColumns.joined(extra)
                extra = [from_extra.kept([self._keep_node_from_extra(node) for node in from_extra.nodes])]
            parts.extend(extra)
        return RecordColumns.joined(parts)

    def _take_into(self, parts: list[RecordColumns], subscription: Any, limit: int, keep: Any) -> int:
        """Take up to ``limit`` messages into ``parts`` (those ``keep(info)`` accepts); how many taken.

        The hot loop of the app: messages are taken first, then decoded all in one call.
        """
        decoder = self.decoder
        if decoder is not None and self.compiled is not None:
            return self._take_compiled(parts, subscription, limit, decoder, keep)
        take, msg_type = subscription.handle.take_message, self.msg_type
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
                parts.append(decoder.decode_columns(messages, self.topic, self._read_refused))
                self.decoder = None  # an rclpy that cannot take serialized messages
                return count + self._take_into(parts, subscription, limit - count, keep)
            if taken is None:
                break
            count += 1
            info = taken[1]
            if keep is None or keep(info):
                append(taken[0])
                see(info)
        if not messages:  # (an empty part would make every batch a join of two)
            return count
        if decoder is not None:
            parts.append(decoder.decode_columns(messages, self.topic, self._read_refused))
        else:
            topic = self.topic
            parts.append(RecordColumns.from_records([log_to_record(message, topic) for message in messages]))
        return count

    def _take_compiled(
        self, parts: list[RecordColumns], subscription: Any, limit: int, decoder: LogDecoder, keep: Any
    ) -> int:
        """``_take_into`` with the takes in C: for the main subscription the sequence checks
        too; for the extra one (``keep``) each message's info comes back, with its
        publisher's GID even where rclpy's message info has none (Jazzy), and only the
        messages ``keep`` accepts are checked and kept."""
        assert self.compiled is not None
        gaps = self._gaps(subscription)
        infos: list[dict] | None = None if keep is None else []
        try:
            messages, lost = self.compiled(subscription.handle.pointer, limit, gaps.last_seen, infos)
        except (RuntimeError, AttributeError) as error:  # rcl refused a take, or no pointer: rclpy's take
            self.compiled, self.compiled_problem = None, str(error)
            return self._take_into(parts, subscription, limit, keep)
        taken = len(messages)
        if infos is not None:
            kept = [keep(info) for info in infos]
            for info in itertools.compress(infos, kept):
                gaps.see(info)
            messages = list(itertools.compress(messages, kept))
        self.counts.lost_gaps += lost
        if messages:
            parts.append(decoder.decode_columns(messages, self.topic, self._read_refused))
        return taken

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
