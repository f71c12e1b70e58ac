"""``console-tui run -- ros2 launch PKG FILE`` (or ``roslaunch``): the launch started, what it
prints read as records of its processes, merged with the live ``/rosout``, each message once.

Three streams meet here, each read by one thread of this source:

- the launch's terminal (``launched_command``, read as ``model/formats/launch_output``
  says): each process's lines, its death as an ERROR, tracebacks as one record;
- the live ``/rosout`` (ROS 1 or ROS 2, as the command says: ``ros_of``), an intake
  process of its own feeding ``ros_queue`` (run_app makes it, as for any live session);
- for roslaunch, the nodes' output files in its run folder (``node_outputs``), where what a
  node launched with ``output="log"`` prints goes instead of the terminal.

A message that arrives by two or three of them (a node's log line is on ``/rosout``, on the
terminal or in its output file) is one record (``files/repeats.LiveRepeats``: each record
waits ``HOLD_NS`` for its copies, so the table shows what the launch printed about a
second late). Records of no known process (roslaunch's own lines, a node's unprefixed output)
are named after the launcher (``roslaunch``, ``launch``). ``stop()`` stops the launch as its
terminal's Ctrl+C would (``LaunchedCommand.stop``) and leaves no process of it behind.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import replace
from pathlib import Path

from ...model.formats.launch_output import DEATH_WAIT_NS, DeathAttribution, LaunchLines, clean_line, live_records
from ...model.inert_text import one_line
from ...model.store.intake_queue import IntakeQueue
from ...model.store.record import LogRecord
from ...model.store.record_batch import RecordColumns
from ...ros.ros_version import ROS1, ROS2
from ...system.thread_names import os_named
from ..files.repeats import SIDE_LAUNCH, SIDE_NODE, SIDE_ROSOUT, LiveRepeats
from ..status import SourceStatus
from .launched_command import LaunchedCommand, LaunchFailed
from .node_outputs import NodeOutputs, run_folder

#: How long the terminal may be quiet before what it printed is handed on.
PAUSE_S = 0.05
#: The launchers by program name, and the ROS each runs.
ROS_OF_PROGRAM = {"roslaunch": ROS1, "rosrun": ROS1, "roscore": ROS1, "ros2": ROS2}


def ros_of(command: Sequence[str]) -> int | None:
    """The ROS a command runs (``roslaunch``: 1, ``ros2 launch``: 2), or None (as the environment says)."""
    return ROS_OF_PROGRAM.get(Path(command[0]).name) if command else None


def launcher_name(command: Sequence[str]) -> str:
    """What the launch's own lines are named: ``roslaunch``, ``launch`` (``ros2 launch``), the program."""
    program = Path(command[0]).name if command else "launch"
    return "launch" if program == "ros2" else program


def command_words(command: Sequence[str]) -> str:
    """The command as the status line says it: paths by their names, at most 80 characters
    (``roslaunch two_nodes.launch``)."""
    words = [Path(word).name if "/" in word and " " not in word else word for word in command]
    return one_line(" ".join(words), 80)


class LaunchSource:
    """Runs ``command`` and puts its records, and ``ros_queue``'s, merged, into ``queue``."""

    def __init__(
        self,
        queue: IntakeQueue,
        command: Sequence[str],
        *,
        env: dict[str, str] | None = None,
        clock: Callable[[], int] = time.time_ns,
        say: Callable[[str], None] | None = None,
    ) -> None:
        self.queue = queue
        self.command = list(command)
        self.env = env
        #: The live /rosout's records, to merge with the launch's (an intake process puts them).
        self.ros_queue = IntakeQueue()
        self.clock = clock
        self.say = say
        self.name = launcher_name(command)
        self._parser = LaunchLines()
        # The lines a process printed right after a log line, cut off its copy: its own.
        self.repeats = LiveRepeats(rest_node=self._process_of)
        self.status = SourceStatus(origin=command_words(self.command), path="starting", hint=f"starting {self.name}…")
        self.launched: LaunchedCommand | None = None
        self._outputs: NodeOutputs | None = None
        self._deaths = DeathAttribution()
        self._from_launch: list[LogRecord] = []
        self._started_ns = 0
        self._thread: threading.Thread | None = None
        self._stop_lock = threading.Lock()
        self._stopping = threading.Event()

    @property
    def started(self) -> bool:
        return self._thread is not None

    def start(self) -> None:
        """Start the command (once: run_app starts it before the app is made)."""
        if self.started:
            return
        self._started_ns = self.clock()
        try:
            self.launched = LaunchedCommand(self.command, self.env)
        except LaunchFailed as error:
            self.status = replace(self.status, problem=f"the launch could not start: {error}", path="", hint="")
            self._thread = threading.Thread(target=lambda: None)
            return
        self.status = replace(self.status, path=f"running (pid {self.launched.pid})", running=True)
        self._thread = threading.Thread(target=os_named(self._run), name="console-tui-launch", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        """Stop the launch (SIGINT to its group, escalated) and wait for its last words."""
        with self._stop_lock:
            launched = self.launched
            if launched is not None:
                launched.stop(self.say)
            self._stopping.set()
            thread = self._thread
        if thread is not None and thread is not threading.current_thread() and thread.ident is not None:
            thread.join(5.0)

    # -- the reading thread ----------------------------------------------------------------------

    def _lines(self, launched: LaunchedCommand) -> Iterator[str | None]:
        """The terminal's lines, cleaned; each turn hands on what is due of every stream."""
        for line in launched.lines(PAUSE_S):
            if line is not None:
                line = clean_line(line)
                if self._outputs is None and (folder := run_folder(line)) is not None:
                    self._outputs = NodeOutputs(folder, self._started_ns)
            yield line
            self._hand_on()

    def _run(self) -> None:
        launched = self.launched
        assert launched is not None
        try:
            for record in live_records(self._lines(launched), self.clock, source=self.name, parser=self._parser):
                self._from_launch.append(record)
        except Exception as error:  # the app must learn of it, never die of it
            self.status = replace(self.status, problem=f"reading the launch stopped: {type(error).__name__}: {error}")
        code = launched.process.wait()
        self._hand_on(final=True)
        ended = f"the launch ended (exit status {code})"
        self.status = replace(self.status, path=ended, running=False, hint="")
        # What /rosout still brings (nodes that outlive the launch) keeps coming, merged as before.
        while not self._stopping.wait(PAUSE_S * 4):
            self._hand_on()
        self._hand_on(final=True)
        if self._outputs is not None:
            self._outputs.close()

    def _process_of(self, record: LogRecord) -> str:
        """The node of lines a process printed: the process (a launch's copy names it as its source)."""
        return record.source if record.source in self._parser.processes else record.node

    def _hand_on(self, *, final: bool = False) -> None:
        """What each stream brought into the merger, and what waited long enough into the queue."""
        now = self.clock()
        repeats = self.repeats
        launch_records: list[LogRecord] = []
        for record in self._from_launch:
            launch_records += self._deaths.take(record, now)
        self._from_launch.clear()
        launch_records += self._deaths.due(now + (DEATH_WAIT_NS if final else 0))
        repeats.add(launch_records, SIDE_LAUNCH, now)
        repeats.add(self.ros_queue.drain(), SIDE_ROSOUT, now)
        if self._outputs is not None:
            repeats.add(self._outputs.read(), SIDE_NODE, now)
        out = repeats.flush() if final else repeats.due(now)
        if not out:
            return
        name = self.name
        for record in out:
            if not record.node:
                record.node = name
        out.sort(key=_stamp)  # the streams' copies came a moment apart: in time order
        self.queue.put(RecordColumns.from_records(out))
        if self.status.hint:
            self.status = replace(self.status, hint="")


def _stamp(record: LogRecord) -> int:
    return record.stamp_ns
