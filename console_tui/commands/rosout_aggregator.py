"""The rosout node for ROS 2: every ``/rosout`` message republished on ``/rosout_agg``
with a deep, late-joiner-friendly history, and appended to a ``rosout.log``.

Input comes from the app's own live source (``LiveLogSource`` on ``/rosout`` alone, with
its QoS choice: RELIABLE + TRANSIENT_LOCAL, plus a VOLATILE subscription for publishers
that cannot match it), so the aggregator misses nothing the app would not. It never
reads ``/rosout_agg``, and it publishes only there: two aggregators on one graph do not
feed each other (a console reading ``/rosout_agg`` then hears each message from both,
which the aggregator warns about).

Each record is serialized again (``LogEncoder``) and published as bytes on
``/rosout_agg``, RELIABLE + TRANSIENT_LOCAL, KEEP_LAST ``depth``; the same record is
appended to rosout.log (``rosout_log_text``, rotated by ``RotatingFile``), flushed at
least every ``FLUSH_S``. The node (named ``rosout`` unless told otherwise) logs what it
has done on its own ``/rosout`` every ``report_s`` seconds, and at once when something
goes wrong (messages lost, rosout.log not writable, another aggregator seen).
"""

from __future__ import annotations

import threading
import time
from dataclasses import dataclass

from ..model.formats.ros2_log_msg import LogEncoder
from ..model.formats.rosout_log import rosout_log_text
from ..model.formats.rotating_file import RotatingFile
from ..model.inert_text import plural
from ..model.store.intake_queue import IntakeQueue
from ..model.store.record import LogRecord
from ..ros.ros2.runtime import RosRuntime
from ..sources.log_topics import ROSOUT, ROSOUT_AGG
from ..sources.ros2.live_source import LiveLogSource

DEFAULT_DEPTH = 10_000
DEFAULT_NODE_NAME = "rosout"
DEFAULT_REPORT_S = 60.0
#: Longest a written message waits in our buffer before the operating system has it.
FLUSH_S = 0.2
#: How often the queue is drained (and published) when messages trickle in.
POLL_S = 0.02
#: How often the graph is looked at for other aggregators.
GRAPH_S = 5.0
#: Records waiting to be forwarded, at most (about 10 s at 20k/s); past that they are
#: counted as lost rather than kept, so a stalled aggregator cannot eat the robot's memory.
QUEUE_LIMIT = 200_000


@dataclass(frozen=True)
class AggregatorCounts:
    """What the aggregator has done so far."""

    received: int
    published: int
    written: int
    #: Lost before they reached us (middleware, queue), as the live source counts them.
    lost: int
    #: Records that could not be serialized again (never expected).
    unencodable: int
    #: Lines rosout.log could not take.
    not_written: int
    publishers: int
    subscribers: int


class RosoutAggregator:
    """``run(stop)`` aggregates until ``stop`` is set; ``counts()`` from any thread."""

    def __init__(
        self,
        runtime: RosRuntime,
        *,
        depth: int = DEFAULT_DEPTH,
        log: RotatingFile | None = None,
        node_name: str = DEFAULT_NODE_NAME,
        report_s: float = DEFAULT_REPORT_S,
    ) -> None:
        from rcl_interfaces.msg import Log
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        self.runtime = runtime
        self.depth = depth
        self.log = log
        self.report_s = report_s
        self.node = runtime.create_node("rosout", name=node_name, enable_rosout=True)
        self.logger = self.node.get_logger()
        qos = QoSProfile(
            history=HistoryPolicy.KEEP_LAST,
            depth=depth,
            reliability=ReliabilityPolicy.RELIABLE,
            durability=DurabilityPolicy.TRANSIENT_LOCAL,
        )
        self.publisher = self.node.create_publisher(Log, ROSOUT_AGG, qos)
        self.queue = IntakeQueue(limit=QUEUE_LIMIT)
        self.source = LiveLogSource(runtime, self.queue, topic=ROSOUT)
        self.encoder = LogEncoder()
        self._received = self._published = self._unencodable = 0
        self._lock = threading.Lock()
        self._aggregators = 1
        self._reported_lost = 0
        self._reported_error = ""

    # -- running ----------------------------------------------------------------------------

    def run(self, stop: threading.Event) -> None:
        """Forward messages until ``stop`` is set, then everything still queued; flushes and
        closes rosout.log at the end."""
        self.source.start()
        where = f"; writing {self.log.path}" if self.log is not None else ""
        self.logger.info(f"republishing {ROSOUT} on {ROSOUT_AGG} (history of {self.depth}){where}")
        now = time.monotonic()
        last_flush, next_report, next_graph = now, now + self.report_s, now + 1.0
        try:
            while not stop.wait(POLL_S):
                self.forward(self.queue.drain())
                now = time.monotonic()
                if now - last_flush >= FLUSH_S:
                    last_flush = now
                    if self.log is not None:
                        self.log.flush()
                    self._report_problems()
                if now >= next_graph:
                    next_graph = now + GRAPH_S
                    self._look_for_other_aggregators()
                if self.report_s > 0 and now >= next_report:
                    next_report = now + self.report_s
                    self.report()
        finally:
            self.source.stop()
            self.forward(self.queue.drain())
            if self.log is not None:
                self.log.flush()
                self.log.close()

    def forward(self, batch: list[LogRecord]) -> None:
        """Publish and write one batch."""
        if not batch:
            return
        encode, publish = self.encoder.encode, self.publisher.publish
        lines: list[str] = []
        published = unencodable = 0
        for record in batch:
            try:
                data = encode(record)
            except Exception:  # a stamp out of int32's range, for one; never expected
                unencodable += 1
                continue
            publish(data)
            published += 1
            lines.append(rosout_log_text(record))
        if self.log is not None:
            self.log.write(lines)
        with self._lock:
            self._received += len(batch)
            self._published += published
            self._unencodable += unencodable

    # -- reporting --------------------------------------------------------------------------

    def counts(self) -> AggregatorCounts:
        status = self.source.status
        with self._lock:
            received, published, unencodable = self._received, self._published, self._unencodable
        written = self.log.written if self.log is not None else 0
        try:
            subscribers = self.publisher.get_subscription_count()
        except Exception:
            subscribers = 0
        return AggregatorCounts(
            received=received,
            published=published,
            written=written,
            lost=status.lost,
            unencodable=unencodable,
            not_written=self.log.lost if self.log is not None else 0,
            publishers=status.publishers,
            subscribers=subscribers,
        )

    def report(self) -> None:
        """Log the counts on our own /rosout."""
        counts = self.counts()
        text = (
            f"{plural(counts.received, 'message')} from {plural(counts.publishers, 'publisher')}, "
            f"{counts.published:,} republished to {plural(counts.subscribers, 'subscriber')}"
        )
        if self.log is not None:
            text += f", {counts.written:,} written to {self.log.path}"
            if self.log.rotations:
                text += f" (rotated {self.log.rotations} times)"
        text += f"; lost {counts.lost:,}"
        if counts.not_written:
            text += f", not written {counts.not_written:,}"
        self.logger.info(text)

    def _report_problems(self) -> None:
        status = self.source.status
        if status.lost > self._reported_lost:
            self.logger.warning(f"{plural(status.lost - self._reported_lost, 'message')} lost: {status.loss_text()}")
            self._reported_lost = status.lost
        if status.problem and status.problem != self._reported_error:
            self.logger.error(status.problem)
            self._reported_error = status.problem
        log = self.log
        if log is not None and log.error and log.error != self._reported_error:
            self.logger.error(
                f"cannot write rosout.log: {log.error} ({plural(log.lost, 'message')} not written so far)"
            )
            self._reported_error = log.error

    def _look_for_other_aggregators(self) -> None:
        try:
            infos = self.node.get_publishers_info_by_topic(ROSOUT_AGG)
        except Exception:
            return
        # Publishers' GIDs are not ours to see in rclpy: every publisher but one is another's.
        names = sorted(f"{info.node_namespace.rstrip('/')}/{info.node_name}" for info in infos)
        if len(names) > 1 and len(names) > self._aggregators:
            self.logger.warning(
                f"{len(names)} nodes publish {ROSOUT_AGG} ({', '.join(names)}): "
                "a console reading it receives every message from each of them"
            )
        self._aggregators = len(names)
