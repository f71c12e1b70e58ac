"""What the live source counts as lost, and why: the middleware's events and sequence gaps.

Loss is counted, never silent: the middleware's message-lost events, batches the full
``IntakeQueue`` refused, and undecodable messages add up to ``SourceStatus.lost``.
"""

from __future__ import annotations


class LossCounts:
    """What the intake thread counts as it goes; turned into ``SourceStatus`` fields.

    Loss in the middleware is counted twice over, and the larger count shown: by the
    middleware's message-lost events (``lost_qos``), and by the gaps in each publisher's
    sequence numbers (``lost_gaps``, see ``SequenceGaps``). Each misses what the other
    sees: Fast DDS reports nothing for messages its reader history overwrote (KEEP_LAST),
    nor, it seems, when the publisher left before telling it; gaps need a publisher GID in
    the message info (Jazzy's rclpy gives none; the take loop in C reads it from rcl) and
    the next message from that publisher. Under a content filter (``filtered``) the writers
    skip what it filters out, gaps that lose nothing: only the events count then.
    """

    __slots__ = (
        "decoded_by_rclpy",
        "filtered",
        "incompatible",
        "last_policy",
        "lost_gaps",
        "lost_qos",
        "lost_undecodable",
    )

    def __init__(self) -> None:
        self.lost_qos = 0
        self.lost_gaps = 0
        self.lost_undecodable = 0
        self.decoded_by_rclpy = 0
        self.incompatible = 0
        self.last_policy = ""
        self.filtered = False

    @property
    def lost_in_middleware(self) -> int:
        return self.lost_qos if self.filtered else max(self.lost_qos, self.lost_gaps)


class SequenceGaps:
    """Messages lost as the gaps in each publisher's sequence numbers show.

    A publisher numbers what it sends 1, 2, 3...; a subscription that got 7 then 10 from
    the same publisher (by GID) lost 2. The first number seen from a publisher starts its
    count (what it sent before we joined is not ours to miss)."""

    __slots__ = ("counts", "last_seen")

    def __init__(self, counts: LossCounts) -> None:
        self.counts = counts
        #: ``{publisher GID: highest sequence number seen}`` (the compiled take updates it too).
        self.last_seen: dict[bytes, int] = {}

    def see(self, info: dict) -> None:
        gid = info.get("publisher_gid")
        number = info.get("publication_sequence_number")
        if not gid or not number:
            return
        key = gid.get("data", b"") if isinstance(gid, dict) else gid
        last = self.last_seen.get(key)
        if last is None or number > last:
            if last is not None and number > last + 1:
                self.counts.lost_gaps += number - last - 1
            self.last_seen[key] = number
