"""Logger levels without ROS: node and logger names, the loggers offered per node, temporary levels.

ROS 2 logger names are dotted: a node ``talker`` in namespace ``/ns`` logs as ``ns.talker``,
its child loggers as ``ns.talker.child``, and ``""`` is the process default. A logger with
no level of its own (level 0, unset) inherits from its nearest dotted ancestor that has
one, and finally from the default. No service lists a node's loggers, so the names offered
for a node come from its own logger name, the child loggers seen in log records, the
default, and names the user types.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Collection, Iterable, Mapping
from dataclasses import dataclass, replace
from enum import Enum

from ..levels import Severity, severity_name

#: The process-wide default logger.
DEFAULT_LOGGER = ""

#: One line telling how to give a node the logger services.
ENABLE_LOGGER_SERVICE_HINT = (
    "enable them with Node(..., enable_logger_service=True) in rclpy "
    "or NodeOptions().enable_logger_service(true) in rclcpp (ROS 2 Iron or later)"
)

#: Node names starting with this are console-tui's own nodes, never listed.
OWN_NODE_PREFIX = "_console_tui_"


def node_logger_name(namespace: str, name: str) -> str:
    """The logger name of node ``name`` in ``namespace``: ``("/ns/sub", "talker")`` -> ``ns.sub.talker``."""
    parts = [part for part in namespace.split("/") if part]
    return ".".join([*parts, name])


def split_fqn(fqn: str) -> tuple[str, str]:
    """A fully qualified node name as ``(namespace, name)``: ``/ns/talker`` -> ``("/ns", "talker")``."""
    namespace, _, name = fqn.rpartition("/")
    return (namespace or "/", name)


def ancestors(logger: str) -> list[str]:
    """The loggers ``logger`` inherits from, nearest first, ending with the default ``""``."""
    if logger == DEFAULT_LOGGER:
        return []
    parts = logger.split(".")
    return [".".join(parts[:end]) for end in range(len(parts) - 1, 0, -1)] + [DEFAULT_LOGGER]


def owner_of(logger: str, node_loggers: Collection[str]) -> str | None:
    """The node logger that ``logger`` is, or is a child of (the longest dotted prefix); else None.

    ``a.b.c`` belongs to ``a.b`` when both ``a`` and ``a.b`` are node loggers, and ``a.bc``
    to ``a``, never to ``a.b``. The default logger belongs to no node.
    """
    if logger == DEFAULT_LOGGER:
        return None
    if logger in node_loggers:
        return logger
    for candidate in ancestors(logger)[:-1]:
        if candidate in node_loggers:
            return candidate
    return None


def effective_level(logger: str, levels: Mapping[str, int]) -> int | None:
    """The level ``logger`` logs at: its own, else its nearest set ancestor's, else the default's.

    Loggers missing from ``levels`` count as unset; None when nothing on the way is known.
    """
    for name in [logger, *ancestors(logger)]:
        level = levels.get(name)
        if level:
            return level
    return None


def level_text(level: int | None) -> str:
    """How a logger's own level reads: ``DEBUG``, ``inherited`` for unset, ``?`` when not read yet."""
    if level is None:
        return "?"
    if level == Severity.UNSET:
        return "inherited"
    return severity_name(level)


def format_remaining(seconds: float) -> str:
    """A countdown: ``9s``, ``1:05``, rounded up so that it reads ``1s`` until the very end."""
    whole = max(0, int(-(-seconds // 1)))
    if whole < 60:
        return f"{whole}s"
    minutes, secs = divmod(whole, 60)
    return f"{minutes}:{secs:02d}"


# -- the graph's nodes --------------------------------------------------------------------


@dataclass(frozen=True, order=True)
class GraphNode:
    """A node of the ROS graph, and whether it offers the logger services; in a fleet, the
    ``robot`` whose graph it is in, which its ``fqn`` names first (``picker:/talker``): the
    same node name on two robots is two nodes."""

    namespace: str
    name: str
    has_logger_services: bool = False
    robot: str = ""

    @property
    def path(self) -> str:
        """Its fully qualified name in its own graph: ``/ns/talker``."""
        return f"{self.namespace.rstrip('/')}/{self.name}"

    @property
    def fqn(self) -> str:
        return robot_qualified(self.robot, self.path)

    @property
    def logger_name(self) -> str:
        return node_logger_name(self.namespace, self.name)

    @property
    def hidden(self) -> bool:
        return self.name.startswith("_")


#: Between a fleet's robot's name and its node's in a node's ``fqn``: ``picker:/talker``.
ROBOT_SEPARATOR = ":"


def robot_qualified(robot: str, node: str) -> str:
    """A node of one robot of a fleet: ``picker:/talker`` (``node`` alone when ``robot`` is
    "": no fleet). The logger pane's nodes, solo and mute, and node rules name nodes so."""
    return f"{robot}{ROBOT_SEPARATOR}{node}" if robot else node


def split_robot(name: str) -> tuple[str, str]:
    """``picker:/talker`` -> (``picker``, ``/talker``); a name of no robot -> ("", name).
    (Neither a ROS node name, a logger name nor a robot's name holds the separator.)"""
    robot, separator, node = name.partition(ROBOT_SEPARATOR)
    return (robot, node) if separator and robot and node else ("", name)


def node_loggers(nodes: Iterable[GraphNode]) -> dict[str, GraphNode]:
    """The nodes by logger name (the first one wins when two nodes share a name)."""
    found: dict[str, GraphNode] = {}
    for node in nodes:
        found.setdefault(node.logger_name, node)
    return found


def node_of_logger(logger: str, nodes: Iterable[GraphNode], robot: str = "") -> GraphNode | None:
    """The node whose messages a record with this logger name is: for "open the pane on this row";
    in a fleet, on the record's ``robot``.

    ROS 1 records carry their node's full name (``/ns/talker``) rather than a logger name."""
    nodes = [node for node in nodes if node.robot == robot] if robot else list(nodes)
    if logger.startswith("/"):
        return next((node for node in nodes if node.path == logger), None)
    by_logger = node_loggers(nodes)
    owner = owner_of(logger, by_logger)
    return None if owner is None else by_logger[owner]


def match_nodes(query: str, nodes: Iterable[GraphNode]) -> list[GraphNode]:
    """The nodes a name typed on the command line means.

    ``/ns/talker`` (fully qualified) or ``ns/talker`` match that node; a bare ``talker`` means
    ``/talker`` if there is one, else every node named ``talker`` in any namespace; a logger
    name such as ``ns.talker`` matches the node that logs under it.
    """
    nodes = list(nodes)
    query = query.strip()
    if "/" in query:
        fqn = query if query.startswith("/") else "/" + query
        return [node for node in nodes if node.fqn == fqn.rstrip("/")]
    exact = [node for node in nodes if node.fqn == "/" + query]
    if exact:
        return exact
    by_name = [node for node in nodes if node.name == query]
    if by_name:
        return by_name
    return [node for node in nodes if node.logger_name == query]


# -- the loggers offered for one node -----------------------------------------------------


class LoggerSource(str, Enum):
    """Why a logger is offered for a node."""

    OWN = "own"
    CHILD = "child"
    TYPED = "typed"
    DEFAULT = "default"
    #: Listed by the node itself (ROS 1's ``get_loggers``).
    LISTED = "listed"


@dataclass(frozen=True)
class TemporaryLevel:
    """A level set for a while; ``previous`` is put back at ``deadline`` (a clock reading)."""

    node: str
    logger: str
    level: int
    previous: int
    deadline: float
    attempts: int = 0

    def remaining(self, now: float) -> float:
        return max(0.0, self.deadline - now)


@dataclass(frozen=True)
class LoggerRow:
    """One line of a node's logger list."""

    name: str
    source: LoggerSource
    #: The logger's own level: 0 when unset (inherited), None when not read yet.
    level: int | None
    #: The level it logs at, through inheritance; None when unknown.
    effective: int | None
    temporary: TemporaryLevel | None = None

    @property
    def level_text(self) -> str:
        """``DEBUG``, or ``inherited (INFO)``, or ``?``."""
        text = level_text(self.level)
        if self.level == Severity.UNSET and self.effective:
            text += f" ({severity_name(self.effective)})"
        return text


class NodeLoggers:
    """The loggers offered for one node and their levels as last read.

    Offered, in this order: the node's own logger, child loggers seen in records, names the
    user typed, and the process default ``""``. ``names_to_read`` adds their ancestors, so
    that inherited levels can be worked out.

    With ``listing`` (ROS 1, whose nodes list their loggers) the loggers offered are those
    the node reported (every name with a level) and the names typed: no own logger, no
    default, and a level read is a level in force (ROS 1 loggers cannot be unset).
    """

    def __init__(self, node: GraphNode, *, listing: bool = False) -> None:
        self.node = node
        self.listing = listing
        self.own = "" if listing else node.logger_name
        self._children: set[str] = set()
        self._typed: list[str] = []
        self.levels: dict[str, int] = {}

    def note_seen(self, logger_names: Iterable[str], all_node_loggers: Collection[str]) -> bool:
        """Take the child loggers among ``logger_names`` (for example the store's node names).

        ``all_node_loggers`` are the logger names of every node of the graph, so that a
        child of a deeper node is not taken. Returns whether a new child was found.
        """
        if self.listing:
            return False
        own = self.own
        prefix = own + "."
        before = len(self._children)
        for name in logger_names:
            if name.startswith(prefix) and owner_of(name, all_node_loggers) in (own, None):
                self._children.add(name)
        return len(self._children) != before

    def add_typed(self, name: str) -> str:
        """Offer a name the user typed (spaces around it dropped); returns the name as kept."""
        name = name.strip()
        if name not in self._typed and name not in self.names():
            self._typed.append(name)
        return name

    def names(self) -> list[str]:
        """The offered names, each once, in display order."""
        if self.listing:
            return list(dict.fromkeys([*sorted(self.levels), *self._typed]))
        ordered = [self.own, *sorted(self._children), *self._typed, DEFAULT_LOGGER]
        return list(dict.fromkeys(ordered))

    def source_of(self, name: str) -> LoggerSource:
        if self.listing:
            return LoggerSource.TYPED if name in self._typed and name not in self.levels else LoggerSource.LISTED
        if name == self.own:
            return LoggerSource.OWN
        if name == DEFAULT_LOGGER:
            return LoggerSource.DEFAULT
        if name in self._children:
            return LoggerSource.CHILD
        return LoggerSource.TYPED

    def names_to_read(self) -> list[str]:
        """The offered names and all their ancestors: what one level read should ask for."""
        wanted: dict[str, None] = {}
        for name in self.names():
            wanted[name] = None
            for ancestor in ancestors(name):
                wanted[ancestor] = None
        return list(wanted)

    def update_levels(self, levels: Mapping[str, int]) -> None:
        """Levels just read from the node, or just set on it."""
        self.levels.update(levels)

    def rows(self, temporaries: Iterable[TemporaryLevel] = ()) -> list[LoggerRow]:
        temporary = {t.logger: t for t in temporaries if t.node == self.node.fqn}
        return [
            LoggerRow(
                name=name,
                source=self.source_of(name),
                level=self.levels.get(name),
                effective=effective_level(name, self.levels),
                temporary=temporary.get(name),
            )
            for name in self.names()
        ]


# -- temporary levels ----------------------------------------------------------------------


class TemporaryLevels:
    """The temporary levels running, by ``(node, logger)``; time comes from ``clock``.

    Not thread-safe: its owner serialises access. Setting a temporary level on a logger
    that already has one keeps the first one's ``previous``: the level that was there before
    any temporary one is what comes back.
    """

    def __init__(self, clock: Callable[[], float] = time.monotonic) -> None:
        self.clock = clock
        self._running: dict[tuple[str, str], TemporaryLevel] = {}

    def start(self, node: str, logger: str, level: int, previous: int, seconds: float) -> TemporaryLevel:
        earlier = self._running.get((node, logger))
        if earlier is not None:
            previous = earlier.previous
        entry = TemporaryLevel(node, logger, level, previous, self.clock() + seconds)
        self._running[(node, logger)] = entry
        return entry

    def get(self, node: str, logger: str) -> TemporaryLevel | None:
        return self._running.get((node, logger))

    def cancel(self, node: str, logger: str) -> TemporaryLevel | None:
        """Forget a temporary level (a level set for good replaces it); returns it."""
        return self._running.pop((node, logger), None)

    def take_due(self) -> list[TemporaryLevel]:
        """Remove and return the entries whose time is up, soonest first."""
        now = self.clock()
        due = sorted((e for e in self._running.values() if e.deadline <= now), key=lambda e: e.deadline)
        for entry in due:
            del self._running[(entry.node, entry.logger)]
        return due

    def take_all(self) -> list[TemporaryLevel]:
        """Remove and return every entry (to restore them all, at exit)."""
        entries, self._running = list(self._running.values()), {}
        return entries

    def retry_later(self, entry: TemporaryLevel, delay: float) -> TemporaryLevel:
        """Put back an entry whose restore failed, due again in ``delay`` seconds."""
        again = replace(entry, deadline=self.clock() + delay, attempts=entry.attempts + 1)
        self._running.setdefault((entry.node, entry.logger), again)
        return again

    def pending(self) -> tuple[TemporaryLevel, ...]:
        return tuple(sorted(self._running.values(), key=lambda e: e.deadline))

    def next_deadline(self) -> float | None:
        return min((e.deadline for e in self._running.values()), default=None)

    def __len__(self) -> int:
        return len(self._running)
