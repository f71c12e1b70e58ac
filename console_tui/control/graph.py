"""The ROS graph as a logger control watches it: its nodes, and when what it says can be believed.

Services are discovered a little after their node, and nodes one after another: a node
without logger services is "checking" until it has been seen long enough
(``GraphSnapshot.settled``), and a graph is complete once it has been watched for a while and
nothing changed for a quiet time (``GraphWatch.wait_for_graph``). The loggers thread gives each
look at the graph to ``GraphWatch.update``; any thread may wait on it.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from ..model.loggers.logger_levels import OWN_NODE_PREFIX, GraphNode, match_nodes

GRAPH_PERIOD_S = 0.5
#: Services are discovered a little after their node: a node is taken to have no logger
#: services once it has been seen this long and shows other services (parameters), or
#: three times as long when it shows none at all.
NO_SERVICES_GRACE_S = 1.5
#: A graph is taken as complete once it has been watched this long and no node has come, gone
#: or changed for the quiet time. Fast DDS repeats its discovery every 3 s, and a node missed
#: by its first round comes seconds later (docs/decisions/0011-waiting-for-discovery.md).
GRAPH_MIN_S = 5.0
GRAPH_QUIET_S = 2.0


@dataclass(frozen=True)
class GraphWait:
    """What ``wait_for_graph`` saw: the nodes, how long it waited, and whether the graph had
    settled (no change for the quiet time, every node's logger services known) or the deadline
    came first."""

    nodes: tuple[GraphNode, ...]
    waited_s: float
    settled: bool


@dataclass
class GraphSnapshot:
    """The graph at one look, and what came before it (when each node was first seen)."""

    nodes: tuple[GraphNode, ...] = ()
    by_fqn: dict[str, GraphNode] = field(default_factory=dict)
    first_seen: dict[str, float] = field(default_factory=dict)
    #: Nodes that show at least one service of any kind.
    with_services: frozenset[str] = frozenset()
    refreshes: int = 0
    #: When the nodes last changed (the first look counts as a change).
    changed_at: float = 0.0

    def quiet_until(self, watched_from: float, min_s: float, quiet_s: float) -> float:
        """When this graph counts as complete if nothing changes: watched for ``min_s`` since
        ``watched_from``, and ``quiet_s`` after its nodes last changed."""
        return max(self.changed_at + quiet_s, watched_from + min_s)

    def settled(self, node: GraphNode, now: float) -> bool:
        """Whether what the graph says of the node's logger services can be believed."""
        if node.has_logger_services:
            return True
        seen_for = now - self.first_seen.get(node.fqn, now)
        grace = NO_SERVICES_GRACE_S if node.fqn in self.with_services else 3 * NO_SERVICES_GRACE_S
        return seen_for >= grace


class GraphWatch:
    """The latest ``GraphSnapshot``, and waiting, from any thread, until it tells enough.

    ``halted()`` says the control has stopped and ``problem()`` what went wrong (""): either
    ends a wait early, the problem once the graph has been looked at.
    """

    def __init__(
        self,
        clock: Callable[[], float],
        *,
        include_hidden: bool,
        halted: Callable[[], bool],
        problem: Callable[[], str],
    ) -> None:
        self.clock = clock
        self.include_hidden = include_hidden
        self.snapshot = GraphSnapshot()
        self._halted = halted
        self._problem = problem
        self._changed = threading.Condition()

    @property
    def refreshes(self) -> int:
        """How many looks at the graph so far."""
        return self.snapshot.refreshes

    def update(self, looked: Iterable[GraphNode], with_services: frozenset[str], now: float) -> bool:
        """Take a look at the graph (console-tui's own nodes, and hidden ones unless
        ``include_hidden``, left out); True when its nodes changed."""
        found = {
            node.fqn: node
            for node in looked
            if not node.name.startswith(OWN_NODE_PREFIX) and (self.include_hidden or not node.hidden)
        }
        nodes = tuple(sorted(found.values(), key=lambda n: n.fqn))
        with self._changed:
            old = self.snapshot
            first_seen = {fqn: old.first_seen.get(fqn, now) for fqn in found}
            changed_at = now if nodes != old.nodes or not old.refreshes else old.changed_at
            self.snapshot = GraphSnapshot(nodes, found, first_seen, with_services, old.refreshes + 1, changed_at)
            self._changed.notify_all()
        return nodes != old.nodes

    def find_node(self, query: str, wait: float) -> list[GraphNode]:
        """Blocking: the nodes ``query`` names (see ``match_nodes``), waiting up to ``wait`` s.

        Returns as soon as a match offers logger services, or has been seen for long enough
        to be sure it has none; at the deadline returns what matches (maybe nothing).
        """
        deadline = self.clock() + wait
        with self._changed:
            while True:
                graph = self.snapshot
                matches = match_nodes(query, graph.nodes)
                now = self.clock()
                settled = any(graph.settled(node, now) for node in matches)
                if settled or now >= deadline or self._halted() or (graph.refreshes and self._problem()):
                    return matches
                self._changed.wait(min(deadline - now, GRAPH_PERIOD_S))

    def wait_for_graph(self, deadline: float, min_s: float, quiet_s: float) -> GraphWait:
        """Blocking: the nodes once the graph has settled, or at the latest after ``deadline`` s.

        Settled: watched for ``min_s`` at least, at least one node, none came, went or changed
        for ``quiet_s``, and what each says of its logger services can be believed. At least
        one look at the graph is always taken, even with a deadline of 0.
        """
        started = self.clock()
        end = started + deadline
        with self._changed:
            while True:
                graph, now = self.snapshot, self.clock()
                looked = graph.refreshes > 0
                quiet_until = graph.quiet_until(started, min_s, quiet_s)
                settled = (
                    looked
                    and bool(graph.nodes)
                    and now >= quiet_until
                    and all(graph.settled(node, now) for node in graph.nodes)
                )
                # A problem (the ROS 1 master does not answer, the control stopped): say it now.
                if settled or (looked and (now >= end or self._problem())) or self._halted():
                    return GraphWait(graph.nodes, now - started, settled)
                wake = min(end, quiet_until) if graph.nodes and now < quiet_until else end
                self._changed.wait(max(0.01, min(wake - now, GRAPH_PERIOD_S)))
