"""A chDB directory asked through a child process (``chdb_child.py``), with the part of
clickhouse-connect's client that ``TableClient`` uses: ``query(sql).result_columns``,
``command``, ``insert``, ``server_version``, ``close``.

The engine's memory (about 260 MB resident) and its crashes stay in the child; the console's
process holds only what the answers are. Every answer is waited for at most the query's time
limit and a margin (``ANSWER_MARGIN_S``); a child that does not answer in that time is killed,
one that died is said with the end of what it printed; either way ``WarehouseError``, and the
next ``TableClient`` starts another. ``close`` waits for the child to end, so that the
directory is free for the next process that opens it.
"""

from __future__ import annotations

import os
import pickle
import select
import subprocess
import sys
import tempfile
from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

from .chdb_child import FRAME, write_frame
from .outcome import WarehouseError

#: Beyond a query's own time limit, how long an answer may take to come.
ANSWER_MARGIN_S = 15.0
#: How long the child may take to open the directory.
START_TIMEOUT_S = 60.0
#: How long closing waits for the child to end before it is killed.
CLOSE_TIMEOUT_S = 10.0
#: The most of the child's standard error quoted when it fails.
STDERR_QUOTED = 300


class _Result(NamedTuple):
    result_columns: list[list[Any]]


class ChdbProcess:
    """The engine in a child process, on ``directory``."""

    def __init__(self, directory: str, *, settings: Mapping[str, Any], timeout: float) -> None:
        self._timeout = timeout + ANSWER_MARGIN_S
        self._stderr = tempfile.TemporaryFile()
        arguments = [directory, pickle.dumps(dict(settings)).hex()]
        self._process: subprocess.Popen[bytes] | None = subprocess.Popen(
            [sys.executable, "-m", "console_tui.warehouse.chdb_child", *arguments],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self._stderr,
        )
        self.server_version = str(self._answer(START_TIMEOUT_S))

    def query(self, sql: str) -> _Result:
        return _Result(self._ask(("columns", sql)))

    def command(self, sql: str) -> Any:
        return self._ask(("command", sql))

    def insert(
        self,
        table: str,
        rows: Sequence[Sequence[Any]],
        *,
        column_names: Sequence[str],
        database: str | None = None,
        settings: Mapping[str, Any] | None = None,
    ) -> None:
        self._ask(("insert", table, [list(row) for row in rows], list(column_names), dict(settings or {})))

    def close(self) -> None:
        process, self._process = self._process, None
        if process is None:
            return
        try:
            assert process.stdin is not None
            process.stdin.close()  # the child's signal to end
            process.wait(CLOSE_TIMEOUT_S)
        except (OSError, subprocess.TimeoutExpired):
            process.kill()
            process.wait()
        finally:
            self._stderr.close()

    # -- the pipe --------------------------------------------------------------------------------

    def _ask(self, request: tuple) -> Any:
        process = self._process
        if process is None:
            raise WarehouseError("the chDB process was closed")
        try:
            assert process.stdin is not None
            write_frame(process.stdin, request)  # type: ignore[arg-type]
        except OSError:
            raise self._failed("the chDB process ended") from None
        return self._answer(self._timeout)

    def _answer(self, timeout: float) -> Any:
        process = self._process
        assert process is not None and process.stdout is not None
        head = self._read(process.stdout.fileno(), FRAME.size, timeout)
        body = self._read(process.stdout.fileno(), FRAME.unpack(head)[0], timeout)
        status, value = pickle.loads(body)
        if status != "ok":
            raise WarehouseError(str(value))
        return value

    def _read(self, fd: int, size: int, timeout: float) -> bytes:
        """``size`` bytes from the child, each piece within ``timeout``."""
        parts: list[bytes] = []
        left = size
        while left:
            ready, _, _ = select.select([fd], [], [], timeout)
            if not ready:
                raise self._failed(f"chDB did not answer within {timeout:.0f} s", kill=True)
            part = os.read(fd, min(left, 1 << 20))
            if not part:
                raise self._failed("the chDB process ended")
            parts.append(part)
            left -= len(part)
        return b"".join(parts)

    def _failed(self, what: str, *, kill: bool = False) -> WarehouseError:
        """``what`` went wrong: the child stopped (killed when ``kill``), said with the end
        of what it printed."""
        process, self._process = self._process, None
        said = ""
        if process is not None:
            if kill or process.poll() is None:
                process.kill()
            code = process.wait()
            self._stderr.seek(0, os.SEEK_END)
            self._stderr.seek(max(self._stderr.tell() - STDERR_QUOTED, 0))
            printed = " ".join(self._stderr.read().decode("utf-8", "replace").split())
            said = f" (exit status {code}{': ' + printed[-STDERR_QUOTED:] if printed else ''})"
            self._stderr.close()
        return WarehouseError(what + said)
