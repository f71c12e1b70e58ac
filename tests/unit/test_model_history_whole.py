"""The whole history with most of it on disk: the rows a rule shows, a search's matches, the
jumps, the timeline, the storms and the nodes' counts over a store whose full chunks went to
disk (two kept in memory, the oldest dropped at the bound on disk) are what they are over the
same records held in memory."""

from __future__ import annotations

from pathlib import Path

from console_tui.model.overview.node_stats import NodeStats
from console_tui.model.overview.shown_follower import sync_together
from console_tui.model.overview.storms import StormRows
from console_tui.model.overview.timeline import Timeline
from console_tui.model.rules import NodeRule, RuleSet, SeverityRule, exclude
from console_tui.model.store.chunk_spill import ChunkSpill
from console_tui.model.store.find_level import find_level, find_node
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.model.store.spill_file import SpillFiles
from console_tui.model.view.log_view import LogView
from console_tui.model.view.search_walk import Search, parse_search
from console_tui.model.view.seek import Seeker, level_hits

S = 1_000_000_000
#: 12 chunks and a half, the oldest three beyond the bound (on disk they go whole chunks at a
#: time: the bound ends where a chunk begins, for both stores to keep the same records).
RECORDS = 12 * CHUNK_SIZE + 2000
BOUND = 9 * CHUNK_SIZE + 2000


def record(i: int) -> LogRecord:
    """Runs of repeats (storms) now and then, every severity, a needle in the oldest records."""
    repeating = (i // 500) % 7 == 3
    return LogRecord(
        stamp_ns=1_700_000_000 * S + i * S // 50,
        level=20 if repeating else (10, 20, 20, 30, 40, 20, 50)[i % 7],
        node="storm" if repeating else f"node{i % 5}",
        msg="the same again" if repeating else ("needle in the hay" if i % 10_007 == 3 else f"message {i}"),
        source="/rosout",
    )


def stores(path: Path) -> tuple[LogStore, LogStore]:
    """The same records in a store on disk and in one in memory, the oldest three chunks gone."""
    spilled = LogStore(
        BOUND, spill=ChunkSpill(SpillFiles(path, segment_bytes=1 << 20, min_free_bytes=0), warm_chunks=2)
    )
    held = LogStore(BOUND, memory_bound=BOUND)
    for store in (spilled, held):
        for first in range(0, RECORDS, 1500):
            store.extend(RecordColumns.from_records([record(i) for i in range(first, min(first + 1500, RECORDS))]))
    assert spilled.first_seq == held.first_seq == 3 * CHUNK_SIZE
    assert spilled.on_disk >= 7 * CHUNK_SIZE and spilled.spill is not None and spilled.spill.warm_count <= 2
    return spilled, held


def everything(store: LogStore) -> dict[str, object]:
    """What the console shows of the whole history: under a rule, searched, jumped, counted."""
    view = LogView(store)
    storms, timeline, nodes = StormRows(store, view), Timeline(store, view), NodeStats(store)
    rules = RuleSet((exclude(SeverityRule.of("debug")), exclude(NodeRule(("node2",)))))
    view.set_rules(rules, first_screen=30)
    while not view.refilter_step(0.001):  # in slices, newest first
        pass
    while not sync_together((storms, timeline), 0.001):
        pass
    while not nodes.sync(0.001):
        pass
    search = Search(view, parse_search("needle"), store.end_seq - 1)
    while not search.step(0.001):
        pass
    seeker = Seeker(view, level_hits(50), store.first_seq, forward=True)
    while not seeker.step(0.001):
        pass
    return {
        "rows": [view.seq_at(row) for row in range(len(view))],
        "storm rows": [storms.seq_at(row) for row in range(len(storms))],
        "storms": storms.storm_count,
        "timeline": timeline.columns(80),
        "nodes": nodes.nodes(),
        "matches": list(search.seqs()),
        "first fatal": seeker.found,
        "first warn": find_level(store, store.first_seq, store.end_seq, 30),
        "last debug": find_level(store, store.first_seq, store.end_seq, 10, 10, last=True),
        "first of node3": find_node(store, store.first_seq, store.end_seq, store.nodes.id_of("node3")),
        "oldest": store.get(store.first_seq),
    }


def test_the_whole_history_on_disk_reads_as_it_does_in_memory(tmp_path):
    spilled, held = stores(tmp_path)
    on_disk, in_memory = everything(spilled), everything(held)
    assert on_disk == in_memory
    rows = on_disk["rows"]
    assert isinstance(rows, list) and rows[0] < spilled.first_seq + CHUNK_SIZE  # the oldest chunk's rows are shown
    assert on_disk["storms"] and on_disk["matches"] and on_disk["first fatal"] is not None
