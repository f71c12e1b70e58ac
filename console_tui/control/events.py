"""What a ``LoggerControl`` tells its listeners (``LoggerControl.subscribe``), on its thread."""

from __future__ import annotations

from dataclasses import dataclass

from ..model.loggers.logger_levels import GraphNode, TemporaryLevel
from .errors import LoggerCallError


@dataclass(frozen=True)
class NodesChanged:
    """The graph's nodes changed (or their logger services appeared)."""

    nodes: tuple[GraphNode, ...]


@dataclass(frozen=True)
class TemporaryEnded:
    """A temporary level is over: ``previous`` restored, or ``error`` says why not."""

    entry: TemporaryLevel
    error: LoggerCallError | None = None


LoggerEvent = NodesChanged | TemporaryEnded
