"""A live source run in a child process (``child``), seen from the app: start, stop, status.

Why a process: docs/decisions/0005-intake-in-its-own-process.md.

A thread of this process reads the pipe: ``BATCH`` frames go into the app's
``IntakeQueue`` as ``RecordColumns`` (no ``LogRecord`` objects are made for them), and
``STATUS`` frames replace ``status``, with what this side's queue dropped added to the
loss. A source of a fleet (``robot``) names its robot on every record and in its status.
``stop()`` closes the child's stdin, which ends it cleanly, and kills it if it has
not ended within ``STOP_TIMEOUT_S``. A child that ends on its own (it crashed, or could
not start ROS) leaves a ``problem`` in the status saying so, with its last words.
"""

from __future__ import annotations

import os
import subprocess
import sys
import threading
from collections import deque
from collections.abc import Mapping, Sequence
from dataclasses import replace

from ...model.inert_text import one_line
from ...model.store.intake_queue import IntakeQueue
from ...model.store.record_batch import BatchError, BatchUnpacker
from ...system.thread_names import os_named
from ..status import SourceStatus
from .frames import BATCH, STATUS, FrameError, read_frames, status_from

STOP_TIMEOUT_S = 0.8
MODULE = "console_tui.sources.intake_process.child"


class ProcessSource:
    """Runs the ``kind`` source (see ``child.FACTORIES``) in a child process, into ``queue``."""

    def __init__(
        self,
        queue: IntakeQueue,
        kind: str,
        *,
        topic: str | None = None,
        args: Sequence[str] = (),
        env: Mapping[str, str] | None = None,
        origin: str = "",
        remark: str = "",
        robot: str = "",
    ) -> None:
        self.queue = queue
        self.kind = kind
        self.topic = topic
        self.args = list(args)
        self.env = dict(os.environ if env is None else env)
        self.origin = origin
        self.remark = remark
        self.robot = robot
        self.status = SourceStatus(topic=topic or "", origin=origin, path="starting", remark=remark, robot=robot)
        self.process: subprocess.Popen | None = None
        self._child_status = self.status
        self._lock = threading.Lock()
        self._stopping = False
        self._reader: threading.Thread | None = None
        self._stderr_tail: deque[str] = deque(maxlen=20)
        self._stderr_reader: threading.Thread | None = None

    @property
    def pid(self) -> int | None:
        return self.process.pid if self.process is not None else None

    @property
    def started(self) -> bool:
        return self._reader is not None

    def start(self) -> None:
        """Start the intake process, from a thread of its own: starting a process stalls the
        caller until the new process runs (a second and more on a busy machine), and the
        caller is the app's event loop. A source started once is not started again: the app
        starts its sources after its first frame, and the one live intake may have been started
        already, before the app was made (``run_app``)."""
        if self.started:
            return
        self._reader = threading.Thread(target=os_named(self._run), name="console-tui-intake-pipe", daemon=True)
        self._reader.start()

    def stop(self, timeout: float = STOP_TIMEOUT_S) -> None:
        with self._lock:
            if self._stopping:
                return
            self._stopping = True
            process = self.process
        if process is not None:
            self._end(process, timeout)
        if self._reader is not None:
            self._reader.join(timeout + 1.0)
        if self._stderr_reader is not None:
            self._stderr_reader.join(1.0)

    @staticmethod
    def _end(process: subprocess.Popen, timeout: float) -> None:
        """Close the process's stdin (it ends cleanly on that), and kill it after ``timeout``."""
        try:
            if process.stdin is not None:
                process.stdin.close()
        except OSError:
            pass
        try:
            process.wait(timeout)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()

    # -- the reading thread ------------------------------------------------------------------

    def _run(self) -> None:
        command = [sys.executable, "-m", MODULE, self.kind, *self.args]
        if self.topic:
            command += ["--topic", self.topic]
        # PR_SET_PDEATHSIG fires when the thread that started the process ends: this one,
        # which reads the process until it ends. (A closed stdin ends it in any case.)
        command += ["--parent", str(os.getpid())]
        try:
            process = subprocess.Popen(
                command, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=self.env
            )
        except OSError as error:
            self.status = replace(self.status, problem=f"the intake process could not start: {error}", running=False)
            return
        with self._lock:
            self.process = process
            stopping = self._stopping
        self._stderr_reader = threading.Thread(target=self._read_stderr, name="console-tui-intake-err", daemon=True)
        self._stderr_reader.start()
        if stopping:  # stop() came while the process was starting
            self._end(process, STOP_TIMEOUT_S)
        self._read(process)

    def _read(self, process: subprocess.Popen) -> None:
        assert process.stdout is not None
        unpacker = BatchUnpacker()
        problem = ""
        try:
            for kind, payload in read_frames(process.stdout.fileno()):
                if kind == BATCH:
                    batch = unpacker.unpack(payload)
                    self.queue.put(batch.of_robot(self.robot) if self.robot else batch)
                    self._show(self._child_status)  # the queue may have dropped it
                elif kind == STATUS:
                    self._child_status = status_from(payload)
                    self._show(self._child_status)
        except (BatchError, FrameError, ValueError, TypeError) as error:
            problem = f"the intake process sent something unreadable: {error}"
            process.kill()
        except OSError:
            pass
        code = process.wait()
        if self._stopping:
            self._show(replace(self._child_status, running=False))
            return
        if not problem:
            if self._stderr_reader is not None:
                self._stderr_reader.join(1.0)
            last = next((line for line in reversed(self._stderr_tail) if line.strip()), "")
            problem = self._child_status.problem or f"the intake process ended (exit status {code})" + (
                f": {one_line(last, 300)}" if last else ""
            )
        self._show(replace(self._child_status, problem=problem, running=False))

    def _show(self, child: SourceStatus) -> None:
        """The child's status, with this side's drops added and our own origin and remark."""
        dropped = self.queue.dropped
        self.status = replace(
            child,
            origin=child.origin or self.origin,
            remark=child.remark or self.remark,
            robot=self.robot,
            lost=child.lost + dropped,
            lost_queue=child.lost_queue + dropped,
        )

    def _read_stderr(self) -> None:
        process = self.process
        assert process is not None and process.stderr is not None
        for raw in process.stderr:
            self._stderr_tail.append(raw.decode("utf-8", "replace").rstrip("\n"))
