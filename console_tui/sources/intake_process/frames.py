"""What the intake process sends the app on its pipe: frames of record batches and status.

A frame is a 1-byte kind, a 4-byte length (native order) and that many bytes:

- ``BATCH``: records packed by ``model.store.record_batch.BatchPacker`` (in order: the string
  table goes along the stream);
- ``STATUS``: the source's ``SourceStatus`` as a JSON object, sent whenever it changes.

The app never writes to the intake process; closing the process's stdin stops it.
"""

from __future__ import annotations

import json
import os
import struct
from collections.abc import Iterator
from dataclasses import asdict, fields

from ..status import SourceStatus

BATCH = 1
STATUS = 2
_HEADER = struct.Struct("=BI")
READ_BYTES = 1 << 20
#: A frame longer than this is taken for a broken stream (batches are a few hundred kB).
MAX_FRAME = 1 << 30
_STATUS_FIELDS = frozenset(field.name for field in fields(SourceStatus))


class FrameError(ValueError):
    """The stream is not a stream of frames."""


def write_frame(fd: int, kind: int, payload: bytes) -> None:
    """Write one whole frame to ``fd`` (blocking until it is all written)."""
    data = memoryview(_HEADER.pack(kind, len(payload)) + payload)
    while data:
        written = os.write(fd, data)
        data = data[written:]


def status_payload(status: SourceStatus) -> bytes:
    return json.dumps(asdict(status)).encode()


def status_from(payload: bytes) -> SourceStatus:
    """The status a ``STATUS`` frame holds (fields this version does not know are left out)."""
    values = json.loads(payload)
    if not isinstance(values, dict):
        raise FrameError("a status frame that is no JSON object")
    return SourceStatus(**{key: value for key, value in values.items() if key in _STATUS_FIELDS})


def read_frames(fd: int) -> Iterator[tuple[int, bytes]]:
    """The frames read from ``fd`` until it ends (a frame cut short at the end is dropped)."""
    buffer = bytearray()
    while True:
        chunk = os.read(fd, READ_BYTES)
        if not chunk:
            return
        buffer += chunk
        start = 0
        while len(buffer) - start >= _HEADER.size:
            kind, length = _HEADER.unpack_from(buffer, start)
            if length > MAX_FRAME:
                raise FrameError(f"a frame of {length:,} bytes")
            end = start + _HEADER.size + length
            if end > len(buffer):
                break
            yield kind, bytes(buffer[start + _HEADER.size : end])
            start = end
        del buffer[:start]
