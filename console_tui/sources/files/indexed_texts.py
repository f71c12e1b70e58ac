"""A log file's messages read again by byte range: the ``TextSource`` of a file read by index.

The store keeps a file's chunks as columns and byte ranges (``model/indexed_chunk.py``); when
a chunk's messages are read, this reads its bytes again (``os.pread`` on the file opened once,
so a log rotated away is still read) and parses them as the index did: with the scanner in
C where the bytes allow it (``rcutils_scan.c``), else with the format's own reader (after
the file's header, for a format that needs it). The records found must be the index's: as
many, with the same stamps. When they are not, the file changed after it was read
(truncated, rewritten): those messages are placeholders that say so, and ``problem`` says it
for the status line. Nothing here raises.
"""

from __future__ import annotations

import io
import os
from array import array
from itertools import accumulate, repeat
from operator import add
from pathlib import Path

from ...model.formats import Problems, TextFormat, TextLines
from ...model.formats.rcutils_log import RcutilsLogFormat
from ...model.store.chunk import INT64_MAX
from ...model.store.chunk_blob import FileTexts
from ...model.store.packed_texts import PackedTexts
from .compiled_scan import Scanner


def clamped(stamp: int) -> int:
    """A stamp as the store keeps it (``int64``)."""
    return min(max(stamp, -INT64_MAX), INT64_MAX)


def _contains(data: bytes, needle: bytes, lower: bool) -> bool:
    """The scanner's ``contains``, without the scanner."""
    return needle in (data.lower() if lower else data)


class IndexedTexts:
    """Reads the messages of ``path``'s byte ranges again (see the module)."""

    def __init__(
        self, path: Path, text_format: TextFormat, source: str, *, scanner: Scanner | None, header: bytes = b""
    ) -> None:
        self.path = path
        self.format = text_format
        self.source = source
        default = isinstance(text_format, RcutilsLogFormat) and text_format.default_template
        self.scan = scanner.scan if scanner is not None and default else None
        self._contains = scanner.contains if scanner is not None else _contains
        #: The file's lines before its first record, for a format that needs them (CSV's header).
        self.header = header if text_format.needs_header else b""
        self._header_lines = self.header.count(b"\n")
        self.problem = ""
        #: Chunks whose messages could not be read again.
        self.changed = 0
        self._fd: int | None = os.open(path, os.O_RDONLY | os.O_CLOEXEC)

    def close(self) -> None:
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def load(self, texts: FileTexts, stamps: array) -> list[str] | PackedTexts:
        """The messages of bytes ``texts.start:end``, whose records have ``stamps``."""
        found = self._read(texts, stamps)
        if found is None:
            self.changed += 1
            self.problem = (
                f"{self.source} changed after it was read (truncated or written again?): "
                f"the messages of {self.changed * len(stamps):,} records are no longer in it"
            )
            return [f"(no longer in {self.source}: the file changed after it was read)"] * len(stamps)
        if isinstance(found, list):
            return found  # (messages that hold NUL: kept one by one)
        text, starts = found
        return PackedTexts.from_source(text, starts, lambda: self._text_again(texts, stamps))

    def holds(self, texts: FileTexts, needle: bytes, lower: bool) -> bool | None:
        """Whether the bytes ``texts.start:end`` hold ``needle`` (lower-cased ASCII bytes when
        ``lower``), or None when that cannot be told (they cannot be read, or they are not ASCII)."""
        data = self._bytes(texts)
        if data is None:
            return None
        if lower and not data.isascii():
            return None  # (other letters may fold to ASCII ones)
        return self._contains(data, needle, lower)

    def _bytes(self, texts: FileTexts) -> bytes | None:
        """The file's bytes ``texts.start:end`` as they are now (None: not all there)."""
        if self._fd is None:
            return None
        try:
            data = os.pread(self._fd, texts.end - texts.start, texts.start)
        except OSError:
            return None
        return data if len(data) == texts.end - texts.start else None

    def _text_again(self, texts: FileTexts, stamps: array) -> str:
        found = self._read(texts, stamps)
        if isinstance(found, tuple):
            return found[0]
        return "\0".join(["(no longer in the file)"] * len(stamps))

    def _read(self, texts: FileTexts, stamps: array) -> tuple[str, array] | list[str] | None:
        """The messages joined by NUL and where each starts (a list when some hold NUL), or
        None when the bytes do not hold those records any more."""
        data = self._bytes(texts)
        if data is None:
            return None
        count = len(stamps)
        if self.scan is not None:
            status, _stop, found, _lines, scanned, _levels, _ids, messages, starts = self.scan(
                data, 0, len(data), count + 1, {}, [], True, True
            )
            if status == 1:
                if found != count or scanned != stamps.tobytes():
                    return None
                offsets = array("I")
                offsets.frombytes(starts)
                return messages.decode("utf-8"), offsets
        return self._parsed(data, stamps)

    def _parsed(self, data: bytes, stamps: array) -> tuple[str, array] | list[str] | None:
        """What the format's reader makes of the bytes (after the header it needs)."""
        problems = Problems(self.source)  # said when the file was indexed
        lines = TextLines(io.BytesIO(self.header + data), problems)
        records = [
            record
            for line, record in self.format.numbered_records(lines, self.source, problems)
            if line > self._header_lines
        ]
        if len(records) != len(stamps) or [clamped(record.stamp_ns) for record in records] != stamps.tolist():
            return None
        messages = [record.msg for record in records]
        text = "\0".join(messages)
        if text.count("\0") != len(messages) - 1:
            return messages
        return text, array("I", accumulate(map(add, map(len, messages), repeat(1)), initial=0))
