"""The process that holds a chDB directory open for another: ``python -m
console_tui.warehouse.chdb_child DIRECTORY`` (started by ``chdb_process.ChdbProcess``).

chDB is ClickHouse's engine inside the process that opens it: about 260 MB resident once
loaded, and a crash of the engine (a damaged directory) ends that process. So the console
keeps it in this child and asks it over a pipe: each request and answer is a frame
(``FRAME``: its length, then a pickle of a tuple) on standard input and output; the
requests are clickhouse-connect's (``query``'s columns, ``command``, ``insert``), the answers
``("ok", value)`` or ``("error", one line)``. It ends when its standard input does (its
parent closed it or died); Ctrl+C is the parent's to handle.
"""

from __future__ import annotations

import os
import pickle
import signal
import struct
import sys
from typing import Any, BinaryIO

#: A frame's length, before it.
FRAME = struct.Struct(">I")


def read_frame(stream: BinaryIO) -> Any:
    """The next frame's tuple, or None at the end of the stream."""
    head = stream.read(FRAME.size)
    if len(head) < FRAME.size:
        return None
    (size,) = FRAME.unpack(head)
    body = stream.read(size)
    if len(body) < size:
        return None
    return pickle.loads(body)


def write_frame(stream: BinaryIO, value: Any) -> None:
    body = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    stream.write(FRAME.pack(len(body)) + body)
    stream.flush()


def _answer(client: Any, request: tuple) -> Any:
    kind, *args = request
    if kind == "columns":
        return [list(column) for column in client.query(args[0]).result_columns]
    if kind == "command":
        return client.command(args[0])
    if kind == "insert":
        table, rows, column_names, settings = args
        client.insert(table, rows, column_names=column_names, database=None, settings=settings)
        return None
    raise ValueError(f"not a request: {kind!r}")


def main(argv: list[str]) -> int:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent's Ctrl+C: it closes this
    requests, answers = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # nothing but frames on the pipe
    from .driver import clickhouse_driver, describe

    directory, settings = argv[0], pickle.loads(bytes.fromhex(argv[1])) if len(argv) > 1 else {}
    try:
        client = clickhouse_driver().get_client(dsn=f"chdb://{directory}", settings=settings)
    except Exception as error:  # the engine's, of every kind
        write_frame(answers, ("error", describe(error)))
        return 1
    write_frame(answers, ("ok", str(client.server_version)))
    while (request := read_frame(requests)) is not None:
        try:
            write_frame(answers, ("ok", _answer(client, request)))
        except Exception as error:
            write_frame(answers, ("error", describe(error)))
    client.close()
    return 0


if __name__ == "__main__":
    code = main(sys.argv[1:])
    sys.stderr.flush()
    os._exit(code)  # chDB's engine takes a while to tear down, and nobody waits for that
