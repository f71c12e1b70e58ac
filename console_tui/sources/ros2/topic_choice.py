"""Which log topic the live source reads when none is named, and nothing twice when it switches.

``/rosout_agg`` when something publishes it (a rosout node, such as ``console-tui rosout``,
keeps a deep history there), else ``/rosout``. ``/rosout`` is shown at once; when discovery
finds an aggregator, the source switches to it, and its history comes without what
``/rosout`` already gave (docs/decisions/0011-waiting-for-discovery.md).
"""

from __future__ import annotations

from ...model.store.record_batch import RecordColumns
from ..log_topics import ROSOUT

#: How long after the start discovery may still find publishers (an aggregator among them):
#: meanwhile the graph is looked at every ``START_GRAPH_PERIOD_S``.
DISCOVERY_S = 5.0
START_GRAPH_PERIOD_S = 0.1
#: After a switch to ``/rosout_agg``: how long its history is checked against what
#: ``/rosout`` already gave.
SWITCH_DEDUPE_S = 30.0


class TopicChoice:
    """``/rosout_agg`` when something publishes it, else ``/rosout``, never a message twice.

    ``/rosout`` messages go on as they come. When a ``/rosout_agg`` publisher shows up
    (``switched``), its history is delivered without what ``/rosout`` already gave: for each
    logger name, the messages outside the span of time ``/rosout`` covered for it. Those
    older than that span (``/rosout`` keeps only its last 10 s) come after newer ones; the
    app places such a late history by its stamps (``model.store.late_records``).
    """

    def __init__(self, start: float) -> None:
        self.start = start
        #: Per logger name, the oldest and newest stamps ``/rosout`` gave.
        self.oldest: dict[str, int] = {}
        self.newest: dict[str, int] = {}
        self.dedupe_until = 0.0

    def discovering(self, now: float) -> bool:
        """Whether discovery may still find publishers that were there at the start."""
        return now < self.start + DISCOVERY_S

    def switched(self, now: float) -> None:
        """The source reads ``/rosout_agg`` from ``now`` on."""
        self.dedupe_until = now + SWITCH_DEDUPE_S

    def filter(self, batch: RecordColumns, topic: str, now: float) -> RecordColumns:
        """What of ``batch`` (just taken from ``topic``) goes on."""
        if topic == ROSOUT:
            nodes, stamps, oldest = batch.nodes, batch.stamps, self.oldest
            for node in set(nodes).difference(oldest):
                oldest[node] = stamps[nodes.index(node)]
            self.newest.update(zip(nodes, stamps, strict=True))
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
