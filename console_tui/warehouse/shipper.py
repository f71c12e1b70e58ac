"""The loop of ``console-tui ship``: records from the intake into the spool, batches from the
spool to the warehouse, deleted only when it has taken them.

Two threads. The spooler takes what the intake queued every ``flush_s`` (at most
``batch_records`` a batch), makes OpenTelemetry log records of it (``model.formats.otel_log``),
encodes and gzips them (``otlp_encode``) and writes the batch to the spool, whole on the disk.
The sender sends the oldest batch (``targets``); taken, it is deleted; refused for good (a
malformed batch), it is deleted and its records counted as lost; otherwise it is sent again
after a pause that doubles from ``backoff_s`` up to ``max_backoff_s`` (with a little jitter),
or after what the warehouse's ``Retry-After`` asked. A batch too large for the warehouse
(HTTP 413) is sent in halves. ``state()`` says what is happening, for the status line.
"""

from __future__ import annotations

import gzip
import random
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

from ..model.formats.otel_log import otel_logs_of
from ..model.store.indexed_chunk import IndexedChunk
from ..model.store.intake_queue import IntakeQueue
from ..model.store.record_batch import RecordColumns
from .otlp_encode import decode, encode
from .outcome import Outcome
from .spool import Batch, Spool, SpoolState, batch_token
from .targets import Target

#: Records a batch at most (about 40 kB gzipped, well under collectors' request limits).
BATCH_RECORDS = 5_000
FLUSH_S = 0.2
BACKOFF_S = 0.5
MAX_BACKOFF_S = 30.0
#: A batch is halved at most this many times for a warehouse that finds it too large.
MAX_SPLITS = 6


@dataclass(frozen=True)
class ShipState:
    """What the shipper has done: records taken in, sent, waiting, lost, and why it waits."""

    received: int
    sent: int
    spool: SpoolState
    #: Records the warehouse refused for good, or dropped though it took the batch.
    refused: int
    #: Trying again: the problem, and seconds until the next try ("" and 0 when not).
    problem: str
    retry_in: float
    #: Failed tries in a row.
    failures: int

    @property
    def lost(self) -> int:
        return self.refused + self.spool.dropped_records


class Shipper:
    """Ships what ``queue`` receives through ``spool`` to ``target``."""

    def __init__(
        self,
        queue: IntakeQueue,
        spool: Spool,
        target: Target,
        *,
        host: str,
        robot: str = "",
        batch_records: int = BATCH_RECORDS,
        flush_s: float = FLUSH_S,
        backoff_s: float = BACKOFF_S,
        max_backoff_s: float = MAX_BACKOFF_S,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.queue = queue
        self.spool = spool
        self.target = target
        self.host = host
        self.robot = robot
        self.batch_records = batch_records
        self.flush_s = flush_s
        self.backoff_s = backoff_s
        self.max_backoff_s = max_backoff_s
        self.clock = clock
        self._stop = threading.Event()
        self._spooled = threading.Event()  # wakes the sender
        self._lock = threading.Lock()
        self.received = 0
        self.sent = 0
        self.refused = 0
        self._problem = ""
        self._retry_at = 0.0
        self._failures = 0
        self._threads: list[threading.Thread] = []
        #: A problem writing the spool (a full disk), or "".
        self.spool_problem = ""

    # -- running ------------------------------------------------------------------------------

    def start(self) -> None:
        for target, name in ((self._spool_loop, "console-tui-spool"), (self._send_loop, "console-tui-send")):
            thread = threading.Thread(target=target, name=name, daemon=True)
            thread.start()
            self._threads.append(thread)

    def stop(self, timeout: float = 5.0) -> None:
        """Spool what the queue still holds, then stop both threads (the sender ends its try)."""
        self._stop.set()
        self._spooled.set()
        deadline = time.monotonic() + timeout
        for thread in self._threads:
            thread.join(max(deadline - time.monotonic(), 0.0))
        self.target.close()

    def state(self) -> ShipState:
        with self._lock:
            retry_in = max(self._retry_at - self.clock(), 0.0) if self._problem else 0.0
            return ShipState(
                self.received, self.sent, self.spool.state(), self.refused, self._problem, retry_in, self._failures
            )

    # -- into the spool -----------------------------------------------------------------------

    def _spool_loop(self) -> None:
        while True:
            stopping = self._stop.wait(self.flush_s)
            self.spool_queued()
            if stopping:
                return

    def spool_queued(self) -> int:
        """Write what the queue holds to the spool, ``batch_records`` a batch; how many records."""
        written = 0
        while True:
            batches = [
                batch.with_messages() if isinstance(batch, IndexedChunk) else batch
                for batch in self.queue.drain_batches(self.batch_records)
            ]
            if not batches:
                return written
            columns = batches[0] if len(batches) == 1 else RecordColumns.joined(batches)
            observed = time.time_ns()
            for start in range(0, len(columns), self.batch_records):
                part = columns.slice(start, start + self.batch_records)
                logs = otel_logs_of(part, host=self.host, robot=self.robot, observed_ns=observed)
                data = gzip.compress(encode(logs), compresslevel=6, mtime=0)
                try:
                    self.spool.write(data, len(logs))
                except OSError as error:  # a full disk: these records are lost, and said
                    with self._lock:
                        self.refused += len(logs)
                    self.spool_problem = f"cannot write the spool: {error.strerror or error}"
                    continue
                self.spool_problem = ""
                with self._lock:
                    self.received += len(logs)
                written += len(logs)
            self._spooled.set()

    # -- out of the spool ---------------------------------------------------------------------

    def _send_loop(self) -> None:
        while True:
            batch = self.spool.oldest()
            if batch is None:
                if self._stop.is_set():
                    return
                self._spooled.wait(0.5)
                self._spooled.clear()
                continue
            if self._stop.is_set():
                return  # what is left stays in the spool for the next start
            pause = self.send_one(batch)
            if pause:
                self._stop.wait(pause)

    def send_one(self, batch: Batch) -> float:
        """Send one batch; the seconds to wait before the next try (0: go on at once)."""
        self.spool.sending = batch.number
        try:
            data = self.spool.read(batch)
            if data is None:  # dropped meanwhile (the spool was full): counted there
                return 0.0
            outcome = self._send(data, batch.records, 0)
        finally:
            self.spool.sending = None
        if outcome.taken:
            self.spool.delete(batch)
            with self._lock:
                self.sent += batch.records - outcome.rejected
                self.refused += outcome.rejected
                self._problem, self._failures = "", 0
            return 0.0
        if not outcome.retry:  # refused for good
            self.spool.delete(batch)
            with self._lock:
                self.refused += batch.records
                self._problem, self._failures = "", 0
            return 0.0
        with self._lock:
            self._failures += 1
            pause = float(min(self.backoff_s * 2.0 ** (self._failures - 1), self.max_backoff_s))
            pause *= random.uniform(0.8, 1.2)
            if outcome.retry_after is not None:
                pause = float(outcome.retry_after)
            self._problem = outcome.problem or "the warehouse did not take the batch"
            self._retry_at = self.clock() + pause
        return pause

    def _send(self, data: bytes, records: int, splits: int) -> Outcome:
        outcome = self.target.send(data, records, batch_token(data))
        if not outcome.too_large or splits >= MAX_SPLITS or records < 2:
            return outcome
        logs = decode(gzip.decompress(data))
        middle = len(logs) // 2
        for part in (logs[:middle], logs[middle:]):
            piece = gzip.compress(encode(part), compresslevel=6, mtime=0)
            outcome = self._send(piece, len(part), splits + 1)
            if not outcome.taken:
                return outcome  # the whole batch again later (its first half may arrive twice)
        return Outcome(True)
