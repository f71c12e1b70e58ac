"""Taking shown records into runs of repeats (``StormRows``'s part that sees every record).

A record repeats when the last shown record of its node had the same severity, source and
text (key). ``take_each`` looks at one record at a time. ``take_bulk`` finds the repeats of
a whole piece with C-level operations (the piece's records sorted by node, each compared
with the one before it) and looks only at those in Python: most records of a log repeat
nothing, and taking a million of them in again after a rule change is what a recount costs.
``take_distinct`` does it for records of which no two have the same text: only each node's
first record there can repeat (its run from before), so no text but those is read.
``take_apart`` takes a piece of a full chunk in as both: the records of the nodes that have
a text repeated in the chunk (``repeating_nodes``, worked out once a chunk) by ``take_bulk``,
the others by ``take_distinct``.
"""

from __future__ import annotations

from array import array
from collections import Counter
from collections.abc import Callable, Sequence
from itertools import compress, filterfalse
from operator import and_, eq, itemgetter, not_
from typing import TYPE_CHECKING

from ..store.packed_texts import PackedTexts
from ..view.shown_rows import ShownPiece

if TYPE_CHECKING:
    from ..store.log_store import Chunk


class Storm:
    """A run of one node's repeats: its first and last seq, and how many shown messages."""

    __slots__ = ("count", "expanded", "head", "key", "last", "level", "members", "node", "source")

    def __init__(self, head: int, node: int, level: int, source: int, key: str) -> None:
        self.head = head
        self.last = head
        self.count = 1
        self.node = node
        self.level = level
        self.source = source
        self.key = key
        self.expanded = False
        #: While expanded: the seqs after the head, which are rows then.
        self.members: array | None = None


def take_each(
    seqs: Sequence[int],
    columns: tuple[Sequence[int], Sequence[int], Sequence[int], Sequence[str]],
    runs: dict[int, Storm],
    storms: dict[int, Storm],
    rows: array,
) -> None:
    """Take records (``columns``: their nodes, levels, sources, keys) in one by one: runs
    per node in ``runs``, storms by first seq in ``storms``, the rows appended to ``rows``."""
    for seq, node, level, source, key in zip(seqs, *columns, strict=False):
        run = runs.get(node)
        if run is not None and run.key == key and run.level == level and run.source == source:
            run.count += 1
            run.last = seq
            if run.count == 2:
                storms[run.head] = run
            if run.expanded:
                rows.append(seq)
                run.members.append(seq)  # type: ignore[union-attr]  # expanded: it has members
        elif run is not None and run.count == 1 and not run.expanded:
            # The node's last message stayed on its own (no storm holds it): its run
            # starts again here, without a new object for every message.
            rows.append(seq)
            run.head = run.last = seq
            run.level, run.source, run.key = level, source, key
        else:
            rows.append(seq)
            runs[node] = Storm(seq, node, level, source, key)


def take_distinct(
    piece: ShownPiece,
    msgs: Sequence[str],
    mask: Callable[[str], str] | None,
    runs: dict[int, Storm],
    storms: dict[int, Storm],
    rows: array,
) -> None:
    """What ``take_bulk`` does, when no two of the piece's texts (as compared) are the same."""
    chunk, base, offsets = piece.chunk, piece.base, piece.offsets
    nodes, levels, sources = chunk.nodes, chunk.levels, chunk.sources
    picked = _pick(nodes, offsets)
    # Each node's first and last offset here (a dict built from the end keeps the first).
    firsts = dict(zip(reversed(picked), reversed(offsets), strict=False))
    lasts = dict(zip(picked, offsets, strict=False))

    def key(at: int) -> str:
        return msgs[at] if mask is None else mask(msgs[at])

    continued = set()
    for node, at in firsts.items():
        run = runs.get(node)
        if run is not None and run.level == levels[at] and run.source == sources[at] and run.key == key(at):
            continued.add(at)
            run.count += 1
            run.last = base + at
            if run.count == 2:
                storms[run.head] = run
    if continued:
        gone = {base + at for at in continued}
        rows.extend(filterfalse(gone.__contains__, piece.seqs()))
    else:
        rows.extend(piece.seqs())
    # Each node's run is its last record's now (a run continued by it goes on).
    for node, at in lasts.items():
        if at in continued:
            continue
        run = runs.get(node)
        if run is not None and run.count == 1 and not run.expanded:
            run.head = run.last = base + at
            run.level, run.source, run.key = levels[at], sources[at], key(at)
        else:
            runs[node] = Storm(base + at, node, levels[at], sources[at], key(at))


def take_bulk(
    piece: ShownPiece,
    msgs: Sequence[str],
    mask: Callable[[str], str] | None,
    runs: dict[int, Storm],
    storms: dict[int, Storm],
    rows: array,
) -> None:
    """What ``take_each`` does, for the records of ``piece`` (``msgs``: its chunk's texts,
    ``mask``: what texts are compared as), when no run is expanded."""
    chunk, base = piece.chunk, piece.base
    nodes, levels, sources = chunk.nodes, chunk.levels, chunk.sources
    order = sorted(piece.offsets, key=nodes.__getitem__)  # by node, in seq order within each
    count = len(order)

    def by_node(column: Sequence) -> Sequence:
        return _pick(column, order)

    sorted_nodes, texts = by_node(nodes), by_node(msgs)
    if mask is not None:
        texts = [mask(text) for text in texts]
    # repeats[j]: the record at sorted place j repeats the one before it (its node's previous):
    # the texts compared first (they differ most often), the rest only where they are the same.
    repeats = [False, *map(eq, texts[1:], texts)]
    if any(repeats):
        for column in (sorted_nodes, by_node(levels), by_node(sources)):
            repeats[1:] = map(and_, repeats[1:], map(eq, column[1:], column))
    # A node's first record here may repeat its run from before.
    for node, place in dict(zip(reversed(sorted_nodes), range(count - 1, -1, -1), strict=False)).items():
        run = runs.get(node)
        at = order[place]
        if run is not None and run.key == texts[place] and run.level == levels[at] and run.source == sources[at]:
            repeats[place] = True
    places = list(compress(range(count), repeats))
    if not places:
        rows.extend(piece.seqs())
    else:
        gone = {base + at for at in compress(order, repeats)}
        rows.extend(filterfalse(gone.__contains__, piece.seqs()))
        before, node, run = -2, -1, None
        for place in places:
            if place != before + 1 or sorted_nodes[place] != node:
                # A new run of repeats: of the record before it, or of the node's run from before.
                node = sorted_nodes[place]
                if place and sorted_nodes[place - 1] == node:
                    at = order[place - 1]
                    run = runs[node] = Storm(base + at, node, levels[at], sources[at], texts[place - 1])
                else:
                    run = runs[node]
            assert run is not None
            run.count += 1
            run.last = base + order[place]
            if run.count == 2:
                storms[run.head] = run
            before = place
    # Each node's run is its last record's now.
    for node, place in dict(zip(sorted_nodes, range(count), strict=False)).items():
        if repeats[place]:
            continue
        at = order[place]
        run = runs.get(node)
        if run is not None and run.count == 1 and not run.expanded:
            run.head = run.last = base + at
            run.level, run.source, run.key = levels[at], sources[at], texts[place]
        else:
            runs[node] = Storm(base + at, node, levels[at], sources[at], texts[place])


def repeating_nodes(chunk: Chunk, mask: Callable[[str], str] | None) -> frozenset[int]:
    """The nodes of the chunk's records whose text (as compared) another record of the chunk has too."""
    msgs = chunk.msgs
    texts = msgs.texts() if isinstance(msgs, PackedTexts) else list(msgs)
    if mask is not None:
        texts = [mask(text) for text in texts]
    counts = Counter(texts)
    if len(counts) == len(texts):
        return frozenset()
    repeated = {text for text, count in counts.items() if count > 1}
    return frozenset(compress(chunk.nodes, map(repeated.__contains__, texts)))


def take_apart(
    piece: ShownPiece,
    repeating: frozenset[int],
    mask: Callable[[str], str] | None,
    runs: dict[int, Storm],
    storms: dict[int, Storm],
    rows: array,
) -> None:
    """What ``take_bulk`` does, for a piece of a full chunk whose ``repeating_nodes`` are known:
    the records of those nodes by ``take_bulk``, the others by ``take_distinct``."""
    chunk, base, offsets = piece.chunk, piece.base, piece.offsets
    msgs: Sequence[str] = chunk.msgs
    if not repeating:
        take_distinct(piece, msgs, mask, runs, storms, rows)
        return
    among = list(map(repeating.__contains__, _pick(chunk.nodes, offsets)))
    bulk = array("q", compress(offsets, among))
    if isinstance(msgs, PackedTexts) and 8 * len(bulk) >= len(msgs):
        msgs = msgs.texts()  # one split, not a slice of the packed text for each
    if len(bulk) == len(offsets):
        take_bulk(piece, msgs, mask, runs, storms, rows)
        return
    heads = array("q")
    if bulk:
        take_bulk(ShownPiece(chunk, base, bulk), msgs, mask, runs, storms, heads)
    distinct = array("q", compress(offsets, map(not_, among)))
    if distinct:
        take_distinct(ShownPiece(chunk, base, distinct), msgs, mask, runs, storms, heads)
    rows.extend(sorted(heads))


def _pick(column: Sequence, offsets: Sequence[int]) -> Sequence:
    """``column``'s values at ``offsets`` (one or more)."""
    return itemgetter(*offsets)(column) if len(offsets) > 1 else [column[offsets[0]]]
