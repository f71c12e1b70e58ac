"""Per node (logger) statistics for the node panel: messages kept per severity, and the
current rate.

Counts are of the messages kept (the store's bound drops the oldest), whatever the rules
show. A full chunk is counted once and its counts kept until it is evicted; the chunk still
filling and the oldest one (partly evicted) are counted again on each ``refresh``. Counting a
million messages the first time takes steps of a time budget (``refresh`` says when it has
caught up). The rate is of messages arriving, over the last few seconds (``RATE_WINDOW_S``).
"""

from __future__ import annotations

from collections import Counter, deque
from collections.abc import Callable
from dataclasses import dataclass
from itertools import compress
from time import monotonic, perf_counter

from .levels import MESSAGE_SEVERITIES, severity_bucket
from .store import CHUNK_SIZE, Chunk, LogStore

RATE_WINDOW_S = 3.0
_LEVELS = [int(s) for s in MESSAGE_SEVERITIES]
_TABLES = [bytes(1 if severity_bucket(level) == wanted else 0 for level in range(256)) for wanted in _LEVELS]

#: node id -> messages per severity (DEBUG .. FATAL)
Counts = dict[int, list[int]]


@dataclass(frozen=True)
class NodeRow:
    """One node in the panel."""

    name: str
    #: Messages kept per severity: DEBUG, INFO, WARN, ERROR, FATAL.
    counts: tuple[int, ...]
    #: Messages a second arriving now, or None before it is known.
    rate: float | None

    @property
    def total(self) -> int:
        return sum(self.counts)

    @property
    def errors(self) -> int:
        """ERROR and FATAL."""
        return self.counts[3] + self.counts[4]

    @property
    def warnings(self) -> int:
        return self.counts[2]


def count_span(chunk: Chunk, lo: int, hi: int, into: Counts) -> None:
    """Add the messages of ``chunk[lo:hi]`` per node and severity to ``into``."""
    levels = chunk.levels[lo:hi].tobytes()
    nodes = chunk.nodes[lo:hi]
    for index, table in enumerate(_TABLES):
        mask = levels.translate(table)
        if 1 not in mask:
            continue
        for node, number in Counter(compress(nodes, mask)).items():
            row = into.get(node)
            if row is None:
                row = into[node] = [0, 0, 0, 0, 0]
            row[index] += number


def _add(total: Counts, part: Counts, sign: int = 1) -> None:
    for node, numbers in part.items():
        row = total.get(node)
        if row is None:
            row = total[node] = [0, 0, 0, 0, 0]
        for index, number in enumerate(numbers):
            row[index] += sign * number


class NodeStats:
    """Counts per node and severity over a ``LogStore``, kept up to date by ``refresh``."""

    def __init__(self, store: LogStore, clock: Callable[[], float] = monotonic) -> None:
        self.store = store
        self.clock = clock
        #: Counts of each full chunk counted (by its first seq), and their sum.
        self._chunks: dict[int, Counts] = {}
        self._full: Counts = {}
        #: The partly kept and the filling chunks, counted on the last refresh.
        self._partial: Counts = {}
        #: Messages that arrived per node since the start (for rates), and samples of it.
        self._arrived: Counter[int] = Counter()
        self._arrived_to = store.end_seq
        self._samples: deque[tuple[float, Counter[int]]] = deque()
        self.caught_up = False

    def refresh(self, budget_s: float = 0.008) -> bool:
        """Count what changed, for about ``budget_s``; True when the counts are complete."""
        store = self.store
        deadline = perf_counter() + budget_s
        self._count_arrivals()
        spans = list(store.spans(store.first_seq, store.end_seq))
        kept = set()
        partial: Counts = {}
        complete = True
        for span in spans:
            base = span.seq - span.lo
            if span.lo == 0 and span.hi == CHUNK_SIZE:
                kept.add(base)
                if base not in self._chunks:
                    if perf_counter() >= deadline:
                        complete = False
                        continue
                    counts: Counts = {}
                    count_span(span.chunk, 0, CHUNK_SIZE, counts)
                    self._chunks[base] = counts
                    _add(self._full, counts)
            else:
                count_span(span.chunk, span.lo, span.hi, partial)
        for base in [base for base in self._chunks if base not in kept]:
            _add(self._full, self._chunks.pop(base), -1)
        self._partial = partial
        self.caught_up = complete
        return complete

    def _count_arrivals(self) -> None:
        store = self.store
        start = max(self._arrived_to, store.first_seq)
        for span in store.spans(start, store.end_seq):
            self._arrived.update(span.chunk.nodes[span.lo : span.hi])
        self._arrived_to = store.end_seq
        now = self.clock()
        samples = self._samples
        samples.append((now, Counter(self._arrived)))
        while len(samples) > 2 and samples[1][0] <= now - RATE_WINDOW_S:
            samples.popleft()

    def rows(self) -> list[NodeRow]:
        """Every node with messages kept, or that sent some lately, by name."""
        names = self.store.nodes
        counts: Counts = {node: list(numbers) for node, numbers in self._full.items()}
        _add(counts, self._partial)
        rates = self._rates()
        ids = {node for node, numbers in counts.items() if any(numbers)} | {n for n, r in rates.items() if r}
        return sorted(
            (NodeRow(names[node], tuple(counts.get(node, (0, 0, 0, 0, 0))), rates.get(node)) for node in ids),
            key=lambda row: row.name,
        )

    def _rates(self) -> dict[int, float | None]:
        samples = self._samples
        if len(samples) < 2 or samples[-1][0] - samples[0][0] < 0.5:
            return {node: None for node in self._arrived}
        (then, before), (now, after) = samples[0], samples[-1]
        seconds = now - then
        return {node: (after[node] - before[node]) / seconds for node in after}
