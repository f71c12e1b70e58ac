"""How a logger-level call fails: one exception per reason, its ``str()`` the message to show;
the levels never sent."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..model.levels import Severity
from ..model.loggers.logger_levels import DEFAULT_LOGGER


class LoggerCallError(Exception):
    """A logger-level call that failed; ``str()`` is the message to show."""

    def __init__(self, node: str, message: str) -> None:
        super().__init__(message)
        self.node = node


class NodeNotFound(LoggerCallError):
    """No node of that name is in the graph."""

    def __init__(self, node: str) -> None:
        super().__init__(node, f"{node}: no such node in the ROS graph")


class NoLoggerServices(LoggerCallError):
    """The node is there but offers no logger services; ``hint`` says how to give it them."""

    def __init__(self, node: str, hint: str = "") -> None:
        super().__init__(node, f"{node} has no logger services" + (f": {hint}" if hint else ""))


class CallTimedOut(LoggerCallError):
    def __init__(self, node: str, seconds: float) -> None:
        super().__init__(node, f"{node} did not answer within {seconds:g} s (busy, or gone)")


class NodeGone(LoggerCallError):
    def __init__(self, node: str) -> None:
        super().__init__(node, f"{node} went away during the call")


class LevelRefused(LoggerCallError):
    """The node refused some levels; ``refused`` maps each logger name to the node's reason."""

    def __init__(self, node: str, refused: Mapping[str, str]) -> None:
        self.refused = dict(refused)
        details = "; ".join(
            f"{name or '(default)'}: {reason or 'no reason given'}" for name, reason in self.refused.items()
        )
        super().__init__(node, f"{node} refused the level: {details}")


class ControlClosed(LoggerCallError):
    def __init__(self, node: str) -> None:
        super().__init__(node, "logger control is closed")


def call_error(node: str, error: BaseException | None) -> LoggerCallError | None:
    """``error`` as a ``LoggerCallError`` about ``node`` (None stays None)."""
    if error is None or isinstance(error, LoggerCallError):
        return error
    return LoggerCallError(node, f"{node}: {error}")


def unsendable(levels: Mapping[str, Any]) -> dict[str, str]:
    """Why some of ``levels`` are never sent, by logger name (none: empty): a value that is not
    a level number, or the default logger unset."""
    bad = {name: f"not a level: {level!r}" for name, level in levels.items() if not _is_level_number(level)}
    if levels.get(DEFAULT_LOGGER) == Severity.UNSET:
        # rcutils takes it, and the whole process then logs everything: never send it.
        bad[DEFAULT_LOGGER] = "the default logger cannot be unset"
    return bad


def _is_level_number(level: Any) -> bool:
    return isinstance(level, int) and 0 <= level < 2**32
