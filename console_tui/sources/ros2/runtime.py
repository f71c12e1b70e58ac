"""One rclpy context for the whole app, with its own nodes, started and stopped cleanly."""

from __future__ import annotations

import os
import threading
from typing import Any

from .rclpy_loader import load_rclpy


class RosRuntime:
    """Owns an rclpy ``Context`` (not the global one) and the nodes made on it.

    rclpy's signal handlers are not installed: the terminal app handles Ctrl+C itself.
    ``shutdown`` is idempotent and safe to call from any thread.
    """

    def __init__(self, args: list[str] | None = None) -> None:
        rclpy = load_rclpy()
        from rclpy.context import Context
        from rclpy.signals import SignalHandlerOptions

        self._rclpy = rclpy
        self.context = Context()
        rclpy.init(args=args, context=self.context, signal_handler_options=SignalHandlerOptions.NO)
        self._nodes: list[Any] = []
        self._lock = threading.Lock()
        self._closed = False

    def create_node(self, role: str, **options: Any) -> Any:
        """A hidden node (its name starts with ``_``) unique to this process."""
        from rclpy.node import Node

        name = f"_console_tui_{role}_{os.getpid()}"
        node = Node(name, context=self.context, enable_rosout=False, **options)
        with self._lock:
            self._nodes.append(node)
        return node

    @property
    def ok(self) -> bool:
        return not self._closed and self.context.ok()

    def shutdown(self) -> None:
        with self._lock:
            if self._closed:
                return
            self._closed = True
            nodes, self._nodes = self._nodes, []
        for node in nodes:
            try:
                node.destroy_node()
            except Exception:
                pass
        try:
            self.context.try_shutdown()
        except Exception:
            pass
