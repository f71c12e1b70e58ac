"""What follows a store (the view, the storms, the timeline, the node counts) checked against
the same made again over a store that got the same records in one go: after a rewrite of the
store (a late history placed, older pages put before, a source taken out) they must agree."""

from __future__ import annotations

from console_tui.model.overview.node_stats import NodeStats
from console_tui.model.overview.storms import StormRows
from console_tui.model.overview.timeline import Timeline
from console_tui.model.store.log_store import LogStore
from console_tui.model.view.log_view import LogView


def shown(view) -> list[tuple[int, str, str]]:
    """What a view (or the storms' rows) shows, by stamp, node and message."""
    return [(r.stamp_ns, r.node, r.msg) for r in (view.store.get(view.seq_at(row)) for row in range(len(view)))]


def assert_follow_as_made_again(
    view: LogView, storms: StormRows, timeline: Timeline, stats: NodeStats, expected: LogStore
) -> None:
    """``view``, ``storms``, ``timeline`` and ``stats`` (brought up to date) as made over ``expected``."""
    expected_view = LogView(expected, view.rules)
    while not expected_view.refilter_step(1.0):
        pass
    expected_storms, expected_timeline = StormRows(expected, expected_view), Timeline(expected, expected_view)
    for follower in (expected_storms, expected_timeline):
        follower.sync()
    expected_stats = NodeStats(expected)
    expected_stats.update()
    assert shown(view) == shown(expected_view)
    assert shown(storms) == shown(expected_storms)
    assert storms.storm_count == expected_storms.storm_count
    assert timeline.total == expected_timeline.total
    assert [(n.node, n.counts) for n in stats.nodes()] == [(n.node, n.counts) for n in expected_stats.nodes()]
