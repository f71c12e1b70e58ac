"""What native code in this process prints while the app owns the terminal, as records.

Fast DDS and rcutils write straight to file descriptors 1 and 2, below Python and Textual
(an out-of-range ``ROS_DOMAIN_ID``: ``[RTPS Error] Calculated port number is too high``),
so their text would land raw in the middle of the app's screen. While the app runs both
descriptors point into a pipe, and ``sys.__stdout__``/``sys.__stderr__`` (which Textual
draws on and sizes the screen by) at copies of the terminal's. A thread reads the pipe and
puts each line in the intake queue as a record of the node ``console-tui``: shown in the
table, inert like any message, searchable, saved. While the app is suspended (an editor
has the terminal) and after it has ended, the descriptors are the terminal's again; at the
end, what was caught is also written to stderr, so nothing printed is lost.
"""

from __future__ import annotations

import os
import re
import sys
import threading
import time
from collections import deque
from typing import IO, Any

from ..model.inert_text import one_line, strip_colour
from ..model.levels import Severity
from ..model.store.intake_queue import IntakeQueue
from ..model.store.record import LogRecord
from ..model.store.record_batch import RecordColumns

#: The node and source the caught lines are shown under.
NODE = "console-tui"
SOURCE = "native output"
#: The last lines kept for stderr at the end.
KEEP_LINES = 200
#: Lines longer than this are cut (a runaway binary dump must not fill memory).
LINE_LIMIT = 4096

_ERROR = re.compile(r"\b(error|fatal|critical)\b", re.IGNORECASE)
_WARN = re.compile(r"\bwarn(ing)?\b", re.IGNORECASE)


def level_of(line: str) -> int:
    """A guess from the words: ERROR for ``[RTPS Error] ...``, WARN for a warning, else INFO."""
    if _ERROR.search(line):
        return Severity.ERROR
    if _WARN.search(line):
        return Severity.WARN
    return Severity.INFO


class NativeOutput:
    """Catches file descriptors 1 and 2 between ``start`` and ``stop`` (see the module)."""

    def __init__(self, queue: IntakeQueue) -> None:
        self.queue = queue
        self.kept: deque[str] = deque(maxlen=KEEP_LINES)
        self.caught = 0
        self._terminal: tuple[int, int] | None = None
        self._streams: tuple[Any, Any] = (sys.__stdout__, sys.__stderr__)
        self._write = -1
        self._reader: threading.Thread | None = None
        self._lock = threading.Lock()

    @staticmethod
    def possible() -> bool:
        """Only a real terminal is worth guarding (a pipe or a test's capture is left alone), and
        the pipe of a console in a browser (``console-tui serve``): its standard output carries
        the screen's frames, which a stray line of native output would break."""
        if "web_driver" in os.environ.get("TEXTUAL_DRIVER", ""):
            return True
        try:
            return os.isatty(1) and os.isatty(2)
        except OSError:
            return False

    def start(self) -> None:
        read, self._write = os.pipe()
        self._terminal = (os.dup(1), os.dup(2))
        self._streams = (sys.__stdout__, sys.__stderr__)
        # The interpreter's own streams are replaced on purpose (typeshed calls them final).
        sys.__stdout__ = _terminal_stream(self._terminal[0], sys.__stdout__)  # type: ignore[misc,assignment]
        sys.__stderr__ = _terminal_stream(self._terminal[1], sys.__stderr__)  # type: ignore[misc,assignment]
        self._catch()
        self._reader = threading.Thread(target=self._read, args=(read,), name="console-tui-native-output", daemon=True)
        self._reader.start()

    def pause(self) -> None:
        """The terminal's descriptors back while something else draws on it (``resume`` undoes)."""
        if self._terminal is not None:
            _flush()
            os.dup2(self._terminal[0], 1)
            os.dup2(self._terminal[1], 2)

    def resume(self) -> None:
        if self._terminal is not None and self._write >= 0:
            self._catch()

    def stop(self, report: IO[str] | None = None) -> None:
        """The terminal back; what was caught written to ``report`` (stderr by default)."""
        if self._terminal is None:
            return
        self.pause()
        sys.__stdout__, sys.__stderr__ = self._streams  # type: ignore[misc]
        for fd in (*self._terminal, self._write):
            os.close(fd)
        self._terminal, self._write = None, -1
        if self._reader is not None:
            self._reader.join(1.0)  # the pipe's last writer is gone: it reads to the end
        with self._lock:
            lines = list(self.kept)
            caught = self.caught
        if lines:
            out = report or sys.stderr
            more = f" (the last {len(lines)})" if caught > len(lines) else ""
            print(f"console-tui: printed in this process while the console ran{more}:", file=out)
            for line in lines:
                print(f"  {line}", file=out)
            out.flush()

    def _catch(self) -> None:
        _flush()
        os.dup2(self._write, 1)
        os.dup2(self._write, 2)

    def _read(self, read: int) -> None:
        pending = b""
        try:
            while True:
                chunk = os.read(read, 65536)
                if not chunk:
                    break
                pending += chunk
                *lines, pending = pending.split(b"\n")
                if len(pending) > LINE_LIMIT:
                    lines.append(pending)
                    pending = b""
                self._take(lines)
            self._take([pending])
        finally:
            os.close(read)

    def _take(self, lines: list[bytes]) -> None:
        # Fast DDS colours its lines even into a pipe.
        texts = [one_line(strip_colour(line.decode("utf-8", "replace")).rstrip("\r"), LINE_LIMIT) for line in lines]
        texts = [text for text in texts if text.strip()]
        if not texts:
            return
        with self._lock:
            self.kept.extend(texts)
            self.caught += len(texts)
        now = time.time_ns()
        records = [LogRecord(now, level_of(text), NODE, text, source=SOURCE) for text in texts]
        self.queue.put(RecordColumns.from_records(records))


def _terminal_stream(fd: int, like: Any) -> IO[str]:
    """A text stream on ``fd`` (a copy of the terminal's descriptor), encoded as ``like``."""
    encoding = getattr(like, "encoding", None) or "utf-8"
    errors = getattr(like, "errors", None) or "strict"
    return open(fd, "w", buffering=1, encoding=encoding, errors=errors, closefd=False)


def _flush() -> None:
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):
            pass
