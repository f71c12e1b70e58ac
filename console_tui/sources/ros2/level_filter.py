"""A lowest severity asked of the middleware: a DDS content filter on the log subscriptions.

``console-tui tail --level error`` beside a node logging 20,000 DEBUG messages a second should
cost the console nothing for the messages it does not print. As ``ros2 log watch`` does
(ros2cli 0.42, ``ros2log/verb/watch.py``), each subscription is given the content filter
``level >= %0`` with the level as its parameter (``Subscription.set_content_filter``), and
``Subscription.is_cft_enabled`` says whether the middleware took it. Fast DDS (Kilted's rclpy
with ``rmw_fastrtps_cpp``) filters on the writer's side: a message below the level is never
sent to the console. Jazzy's rclpy (7.1) has no content filter calls at all. Where the middleware has no content filter (Cyclone
DDS, Zenoh) or refuses this one, the intake process drops those messages itself after
taking them (``intake_process.child``), and the status says why, once.

A filtered subscription sees gaps in each publisher's sequence numbers (the messages the
writer filtered out); they are not losses (``LossCounts.filtered``).
"""

from __future__ import annotations

import os
from typing import Any

#: ``0`` never asks the middleware (the benchmark's comparison, or a middleware that misbehaves).
SWITCH = "CONSOLE_TUI_CONTENT_FILTER"
EXPRESSION = "level >= %0"
#: Why not, where rclpy has no content filters (Jazzy's 7.1; Kilted's has them).
NO_RCLPY_FILTER = "this rclpy has no content filters (Jazzy's has none)"


def filter_below(subscription: Any, min_level: int) -> str:
    """Ask the middleware to drop what ``subscription`` would receive below ``min_level``;
    ``""`` when it does, else why not (the intake then drops them itself)."""
    if os.environ.get(SWITCH, "") == "0":
        return f"the content filter is switched off: {SWITCH}=0"
    if not hasattr(subscription, "set_content_filter"):
        return NO_RCLPY_FILTER
    try:
        subscription.set_content_filter(EXPRESSION, [str(int(min_level))])
        if subscription.is_cft_enabled:
            return ""
    except Exception as error:  # an rmw without content filters, or an rclpy without the call
        return f"{_middleware()} refused a content filter ({type(error).__name__}: {error})"
    return f"{_middleware()} has no content filter"


def _middleware() -> str:
    try:
        from rclpy import get_rmw_implementation_identifier

        return str(get_rmw_implementation_identifier())
    except Exception:
        return "the middleware"
