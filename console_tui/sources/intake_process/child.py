"""The intake process: a live source run in a process of its own, its records sent to the app.

    python -m console_tui.sources.intake_process.child ros2 [--topic T] [--typed]
    python -m console_tui.sources.intake_process.child ros1 [--topic T]
    python -m console_tui.sources.intake_process.child synthetic [--rate N] [--count N]
    python -m console_tui.sources.intake_process.child journal [--unit U]... [--since T]
        [--journal-file F]... [--journal-directory D] [--log-format TEMPLATE]
    ... [--min-level N]   (only records of that ROS 2 severity and worse: ``tail --level``)

The source (``FACTORIES``) takes and decodes messages with its own thread into an
``IntakeQueue`` of this process, exactly as it would in the app's; every ``FLUSH_S`` the
main thread packs what is waiting into one ``BATCH`` frame (``model.store.record_batch``; at most
``FRAME_RECORDS`` records a frame) and writes it, and the source's status as a ``STATUS``
frame whenever it changed, to the pipe the app reads (see ``frames``). With ``--min-level``
the records below it are dropped before they are sent (ROS 2 asks the middleware to drop
them first: ``ros2/level_filter.py``). While the app is busy,
the pipe and then this process's queue hold what arrives (2 million records at most, then
counted as lost). Why a process: docs/decisions/0005-intake-in-its-own-process.md.

It ends, stopping the source cleanly, when its stdin closes (the app stops it, or the app
died: the kernel closes the app's end of the pipe, even after a SIGKILL), on SIGTERM, and
when the app's process ends (Linux: ``PR_SET_PDEATHSIG``, which fires when the app's thread
that started it ends: the one that reads its pipe until it ends). Ctrl+C in the terminal is
for the app, not for it. Whatever it would print goes to stderr: its stdout carries only
frames.
"""

from __future__ import annotations

import argparse
import ctypes
import gc
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

from ...model.store.intake_queue import IntakeQueue
from ...model.store.record_batch import BatchPacker, RecordColumns
from ...system.signal_stop import SignalStop
from ..status import SourceStatus
from .frames import BATCH, STATUS, status_payload, write_frame

FLUSH_S = 0.02
#: Young collections once this many more container objects were made than freed (Python's
#: default is 700). Decoding a batch makes and frees thousands at once (a transposition of
#: its columns makes an iterator a record): at 700 each batch paid for young collections
#: visiting the batch's lists, a fifth of a ROS 1 message's cost. This process keeps no
#: cycles of its own; what start-up made is frozen out of collections.
YOUNG_COLLECTION_THRESHOLD = 20_000
#: Records in one BATCH frame at most (a frame of a few hundred kB).
FRAME_RECORDS = 4096
_PR_SET_PDEATHSIG = 1

Factory = Callable[[IntakeQueue, argparse.Namespace], tuple[Any, Callable[[], None]]]


def _ros2(queue: IntakeQueue, args: argparse.Namespace) -> tuple[Any, Callable[[], None]]:
    from ...ros.ros2.runtime import RosRuntime
    from ..ros2 import compiled_take
    from ..ros2.live_source import LiveLogSource

    runtime = RosRuntime()

    def cleanup() -> None:
        runtime.shutdown()
        compiled_take.stop_building()  # a compiler still at work would outlive this process

    return LiveLogSource(runtime, queue, topic=args.topic, raw=not args.typed, min_level=args.min_level), cleanup


def _ros1(queue: IntakeQueue, args: argparse.Namespace) -> tuple[Any, Callable[[], None]]:
    from ...system.c_build import stop_building
    from ..ros1.live_source import Ros1LiveSource

    # a compiler still at work on the frame loop would outlive this process
    return Ros1LiveSource(queue, topic=args.topic), stop_building


def _synthetic(queue: IntakeQueue, args: argparse.Namespace) -> tuple[Any, Callable[[], None]]:
    from .synthetic import SyntheticSource

    return SyntheticSource(queue, args.rate, count=args.count), lambda: None


def _journal(queue: IntakeQueue, args: argparse.Namespace) -> tuple[Any, Callable[[], None]]:
    from ..journal.journal_source import JournalSource
    from ..journal.journalctl import JournalQuery

    query = JournalQuery(
        files=tuple(args.journal_file or ()),
        directory=args.journal_directory or "",
        units=tuple(args.unit or ()),
        since=args.since or "",
        follow=True,
    )
    return JournalSource(queue, query, template=args.log_format or ""), lambda: None


#: The sources this process can run: a name, and how to make one (the source and what
#: to call once it has stopped). A source has ``start()``, ``stop()`` and ``status``
#: (a ``SourceStatus``) and puts record batches into the queue it is given.
FACTORIES: dict[str, Factory] = {"ros2": _ros2, "ros1": _ros1, "synthetic": _synthetic, "journal": _journal}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="console_tui.sources.intake_process.child")
    parser.add_argument("kind", choices=sorted(FACTORIES))
    parser.add_argument("--topic")
    parser.add_argument("--typed", action="store_true", help="ROS 2: take typed messages (the slow path)")
    parser.add_argument("--rate", type=float, default=1000.0, help="synthetic: records a second")
    parser.add_argument("--count", type=int, help="synthetic: records in all (default: until stopped)")
    parser.add_argument("--unit", action="append", help="journal: this unit's entries (repeatable)")
    parser.add_argument("--since", help="journal: from this time (journalctl's --since)")
    parser.add_argument("--journal-file", action="append", help="journal: this journal file (repeatable)")
    parser.add_argument("--journal-directory", help="journal: the journal files in this directory")
    parser.add_argument("--log-format", help="journal: the RCUTILS_CONSOLE_OUTPUT_FORMAT of ROS 2 lines")
    parser.add_argument("--min-level", type=int, default=0, help="only records of this ROS 2 severity and worse")
    parser.add_argument("--parent", type=int, help="end when this process (the app) ends")
    return parser


def die_with_parent(parent: int) -> None:
    """Be sent SIGTERM when the app's thread that started us ends (Linux), and end now if
    the app is already gone."""
    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent:
        raise SystemExit(0)


#: Why records below ``--min-level`` are dropped here, for a source that asks no middleware.
NO_CONTENT_FILTER = {"ros1": "ROS 1 has no content filter"}


class Sender:
    """Writes what the source queued (what is below ``min_level`` left out), and its status
    when it changed, to ``fd``."""

    def __init__(self, fd: int, queue: IntakeQueue, min_level: int = 0, kind: str = "") -> None:
        self.fd = fd
        self.queue = queue
        self.min_level = min_level
        self._no_filter = NO_CONTENT_FILTER.get(kind, "this source has no content filter")
        self.packer = BatchPacker()
        self._sent: SourceStatus | None = None

    def flush(self, source: Any) -> None:
        """Send what ``source`` queued, each part after the source's status when that changed:
        the status is read once the part is taken from the queue, so that it tells what came
        before those records (the app learns of a new topic before that topic's history)."""
        while True:
            batches = self.queue.drain_batches(FRAME_RECORDS)
            status = source.status
            if self.min_level and not status.min_level:  # a source that does not filter itself
                status = replace(status, min_level=self.min_level, level_filter_note=self._no_filter)
            if status != self._sent:
                write_frame(self.fd, STATUS, status_payload(status))
                self._sent = status
            if not batches:
                break
            # One frame for all of them: the source puts a batch a turn of its loop (about a
            # hundred records at 50,000/s), and the app pays for each batch it takes in.
            batch = RecordColumns.joined(batches)
            if self.min_level:
                minimum = self.min_level
                batch = batch.kept([level >= minimum for level in batch.levels])
                if not batch:
                    continue
            write_frame(self.fd, BATCH, self.packer.pack(batch))


def serve(source: Any, queue: IntakeQueue, fd: int, stop: threading.Event, min_level: int = 0, kind: str = "") -> None:
    """Run ``source`` (of ``kind``) until ``stop`` is set, sending its records (of
    ``min_level`` and worse) and status to ``fd``."""
    sender = Sender(fd, queue, min_level, kind)
    source.start()
    gc.freeze()
    _, middle, old = gc.get_threshold()
    gc.set_threshold(YOUNG_COLLECTION_THRESHOLD, middle, old)
    try:
        while not stop.wait(FLUSH_S):
            sender.flush(source)
    finally:
        source.stop()
    sender.flush(source)


def _stop_at_end_of_input(stop: threading.Event) -> None:
    try:
        while sys.stdin.buffer.read(4096):
            pass
    except (OSError, ValueError):
        pass
    stop.set()


def main(argv: Sequence[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    fd = os.dup(1)
    os.dup2(2, 1)  # stray prints go to stderr, never between the frames
    stop = SignalStop()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, stop.on_signal)
    if args.parent is not None:
        die_with_parent(args.parent)
    threading.Thread(target=_stop_at_end_of_input, args=(stop,), name="console-tui-stdin", daemon=True).start()
    queue = IntakeQueue()
    try:
        source, cleanup = FACTORIES[args.kind](queue, args)
    except Exception as error:
        problem = f"the live intake could not start: {type(error).__name__}: {error}"
        try:
            write_frame(fd, STATUS, status_payload(SourceStatus(topic=args.topic or "", problem=problem)))
        except OSError:
            pass
        return 2
    try:
        serve(source, queue, fd, stop, args.min_level, args.kind)
    except BrokenPipeError:  # the app is gone
        pass
    except Exception as error:
        status = replace(source.status, problem=f"intake stopped: {type(error).__name__}: {error}", running=False)
        try:
            write_frame(fd, STATUS, status_payload(status))
        except OSError:
            pass
        return 1
    finally:
        cleanup()
    return 0


if __name__ == "__main__":
    exit_code = main()
    # ROS is shut down by now; the interpreter's own ending (libraries' static destructors,
    # Fast DDS's threads) would take longer still, and the app waits for this process.
    sys.stderr.flush()
    os._exit(exit_code)
