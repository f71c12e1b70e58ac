"""Which log topic the live source reads when none is named, and nothing twice when it switches.

``/rosout_agg`` when something publishes it (a rosout node, such as ``console-tui rosout``,
keeps a deep history there), else ``/rosout``. At start, while discovery may still find the
aggregator, ``/rosout`` is held back, so the history comes in time order.
"""

from __future__ import annotations

from ...model.record_batch import RecordColumns
from ..log_topics import ROSOUT

#: At start, ``/rosout`` messages are held back while ``/rosout_agg`` may still be
#: discovered: at least ``AUTO_TOPIC_MIN_S``, until the ``/rosout`` publishers found have
#: not changed for ``AUTO_TOPIC_SETTLED_S``, at most ``AUTO_TOPIC_MAX_S`` (how long discovery
#: takes: docs/architecture.md, "Waiting for discovery").
AUTO_TOPIC_MIN_S = 1.0
AUTO_TOPIC_SETTLED_S = 1.0
AUTO_TOPIC_MAX_S = 5.0
#: After a late switch to ``/rosout_agg``: how long its history is checked against what
#: ``/rosout`` already gave.
SWITCH_DEDUPE_S = 30.0


class TopicChoice:
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
        self.held: list[RecordColumns] = []
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

    def filter(self, batch: RecordColumns, topic: str, now: float) -> RecordColumns:
        """What of ``batch`` (just taken from ``topic``) goes on now, in order."""
        if topic == ROSOUT:
            nodes, stamps, oldest = batch.nodes, batch.stamps, self.oldest
            for node in set(nodes).difference(oldest):
                oldest[node] = stamps[nodes.index(node)]
            self.newest.update(zip(nodes, stamps, strict=True))
            if self.holding(now):
                self.held.append(batch)
                return RecordColumns.joined([])
            if self.held:
                batch, self.held = RecordColumns.joined([*self.held, batch]), []
            return batch
        if now < self.dedupe_until:
            oldest, newest = self.oldest, self.newest
            return batch.kept(
                [
                    node not in newest or not oldest[node] <= stamp <= newest[node]
                    for node, stamp in zip(batch.nodes, batch.stamps, strict=True)
                ]
            )
        if self.newest:
            self.oldest, self.newest = {}, {}
        return batch
