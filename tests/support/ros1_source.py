"""Running the ROS 1 live source in-process for tests, and reading what it took."""

from __future__ import annotations

import time

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
from console_tui.sources.ros1.live_source import Ros1LiveSource

from support.rosproc import PATIENCE_S


class Collected:
    """A started ``Ros1LiveSource`` and every record it delivered so far (``records``)."""

    def __init__(self, topic: str | None = None) -> None:
        self.queue = IntakeQueue()
        self.source = Ros1LiveSource(self.queue, topic=topic)
        self._records: list[LogRecord] = []

    def __enter__(self) -> Collected:
        self.source.start()
        return self

    def __exit__(self, *_exc) -> None:
        self.source.stop()

    @property
    def records(self) -> list[LogRecord]:
        self._records.extend(self.queue.drain())
        return self._records

    @property
    def status(self):
        return self.source.status

    def wait(self, condition, timeout: float = PATIENCE_S, what: str = "the records") -> None:
        deadline = time.monotonic() + timeout
        while not condition(self):
            if time.monotonic() > deadline:
                raise AssertionError(
                    f"timed out waiting for {what}; status {self.status}; "
                    f"{len(self.records)} records, last {self.records[-3:]}"
                )
            time.sleep(0.05)

    def has(self, node: str, msg: str) -> bool:
        return any(r.node == node and r.msg == msg for r in self.records)

    def wait_for(self, node: str, msg_prefix: str, timeout: float = PATIENCE_S) -> None:
        self.wait(
            lambda c: any(r.node == node and r.msg.startswith(msg_prefix) for r in c.records),
            timeout,
            f"{msg_prefix!r} from {node}",
        )
