"""One ROS 1 topic the live source subscribes to: its publishers, our connections, the retries.

The master lists a topic's publishers (at registration, then by ``publisherUpdate``); the
live source connects to each. One that cannot be reached, or whose connection ends, is tried
again, backing off from ``RETRY_FIRST_S`` to ``RETRY_MAX_S``, while the master lists it.
At most ``MAX_CONNECTIONS`` are open or being opened over all topics (``connection_room``);
the publishers left unread for that are counted in the status (``not_read_text``).
"""

from __future__ import annotations

import resource
import time
from collections.abc import Iterable
from dataclasses import dataclass, field

RETRY_FIRST_S = 0.5
RETRY_MAX_S = 10.0


def _open_files_limit() -> int:
    soft, _hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    return soft if soft > 0 else 1024


#: Connections (open or being opened) at most, so many publishers cannot use up the file handles.
MAX_CONNECTIONS = max(16, min(512, _open_files_limit() // 4))


@dataclass
class SubscribedTopic:
    """One subscribed topic: its publishers as the master lists them, and our connections."""

    name: str
    publishers: set[str] = field(default_factory=set)
    connected: set[str] = field(default_factory=set)
    connecting: set[str] = field(default_factory=set)
    retry_at: dict[str, float] = field(default_factory=dict)
    attempts: dict[str, int] = field(default_factory=dict)
    #: Publishers that answered our header with an error, and what they said.
    refused: dict[str, str] = field(default_factory=dict)
    #: Publishers not read because of what they did (a broken stream, no whole answer in
    #: time, a malformed answer), and what that was; not those simply gone.
    trouble: dict[str, str] = field(default_factory=dict)
    registered: bool = False

    def set_publishers(self, publishers: list[str]) -> None:
        """The master's list of publishers now: forget the others, connect to the new ones."""
        self.publishers = set(publishers)
        for uri in list(self.retry_at):
            if uri not in self.publishers:
                del self.retry_at[uri]
                self.attempts.pop(uri, None)
                self.refused.pop(uri, None)
                self.trouble.pop(uri, None)
        now = time.monotonic()
        for uri in self.publishers - self.connected - self.connecting:
            self.retry_at.setdefault(uri, now)

    def due(self, now: float, limit: int) -> list[str]:
        """The publishers to connect to now (``limit`` at most), each marked as connecting."""
        uris: list[str] = []
        for uri, when in list(self.retry_at.items()):
            if len(uris) >= limit:
                break
            if when <= now and uri not in self.connecting and uri not in self.connected:
                del self.retry_at[uri]
                self.connecting.add(uri)
                self.attempts[uri] = self.attempts.get(uri, 0) + 1
                uris.append(uri)
        return uris

    def on_connected(self, uri: str) -> None:
        self.connecting.discard(uri)
        self.connected.add(uri)
        self.attempts.pop(uri, None)
        self.refused.pop(uri, None)
        self.trouble.pop(uri, None)

    def on_failed(self, uri: str, reason: str, refused: bool, trouble: bool = True) -> None:
        """A connection could not be made; ``trouble`` unless the publisher is simply gone."""
        self.connecting.discard(uri)
        if refused:
            self.refused[uri] = reason
        elif trouble:
            self.trouble[uri] = reason
        self.retry_later(uri)

    def on_closed(self, uri: str, trouble: str = "") -> None:
        """The connection ended: ``trouble`` says what was wrong with it ("" for a plain end)."""
        self.connected.discard(uri)
        if trouble:
            self.trouble[uri] = trouble
        self.attempts[uri] = 0
        self.retry_later(uri)

    def retry_later(self, uri: str) -> None:
        if uri in self.publishers and uri not in self.connected:
            attempts = self.attempts.get(uri, 0)
            delay = min(RETRY_FIRST_S * (2 ** max(attempts - 1, 0)), RETRY_MAX_S)
            self.retry_at[uri] = time.monotonic() + delay

    def unreachable(self) -> bool:
        """Every publisher the master lists was tried and none could be reached."""
        return (
            bool(self.publishers)
            and not self.connected
            and not self.connecting
            and all(self.attempts.get(uri, 0) >= 1 for uri in self.publishers)
            and not self.refused
        )

    def trouble_text(self) -> str:
        """The first publisher not read because of what it did, and why (and how many more)."""
        uri, reason = next(iter(self.trouble.items()))
        more = len(self.trouble) - 1
        return f"publisher {uri} not read: {reason}" + (f" (and {more} more)" if more else "")


def _open(topics: Iterable[SubscribedTopic]) -> int:
    return sum(len(topic.connected) + len(topic.connecting) for topic in topics)


def connection_room(topics: Iterable[SubscribedTopic]) -> int:
    """How many more connections may be opened now."""
    return max(MAX_CONNECTIONS - _open(topics), 0)


def not_read_text(topics: Iterable[SubscribedTopic]) -> str:
    """How many publishers are left unread because ``MAX_CONNECTIONS`` are open, or ""."""
    topics = list(topics)
    if _open(topics) < MAX_CONNECTIONS:
        return ""
    waiting = sum(len(t.publishers - t.connected - t.connecting) for t in topics)
    return f"{waiting} publishers not read: at most {MAX_CONNECTIONS} connections at once" if waiting else ""
