"""What a source reports about itself, for the status bar."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class SourceStatus:
    """A snapshot of a live source's state, replaced (not mutated) by the source thread."""

    topic: str = ""
    publishers: int = 0
    #: How messages are taken and decoded, for example ``raw+cdr`` or ``typed``.
    path: str = ""
    #: Messages known lost: QoS events, and incompatible publishers not recovered.
    lost: int = 0
    #: A one-line problem the user should see, or "".
    problem: str = ""
    running: bool = False
