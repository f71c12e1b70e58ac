"""Real journal files for the tests: entries written in the journal's export format and
turned into ``*.journal`` files by Debian's ``systemd-journal-remote`` (no systemd needed),
read back by ``journalctl`` as console-tui reads them.

``scripts/test`` installs systemd-journal-remote (as root, with apt-get); where it cannot,
the tests that need it skip, saying why.
"""

from __future__ import annotations

import shutil
import struct
import subprocess
from collections.abc import Mapping, Sequence
from pathlib import Path

import pytest

#: Debian puts it outside PATH.
JOURNAL_REMOTE = ("/lib/systemd/systemd-journal-remote", "/usr/lib/systemd/systemd-journal-remote")
BOOT_ID = "0123456789abcdef0123456789abcdef"


def journal_remote() -> str:
    """systemd-journal-remote's path, or the test skips saying why."""
    found = next((path for path in JOURNAL_REMOTE if Path(path).exists()), None) or shutil.which(
        "systemd-journal-remote"
    )
    if found is None or shutil.which("journalctl") is None:
        pytest.skip(
            "systemd-journal-remote (and journalctl) are not installed: the tests of real journal files need "
            "Debian's systemd-journal-remote (scripts/test installs it when run as root)"
        )
    return found


def export_entry(fields: Mapping[str, str | bytes], stamp_us: int, number: int) -> bytes:
    """One entry in the journal export format (``systemd-journal-export``'s): ``NAME=value``
    lines, a value with a newline or other bytes as ``NAME``, newline, 64-bit length, bytes."""
    out = bytearray()
    base = {
        "__CURSOR": f"s=0;i={number}",
        "__REALTIME_TIMESTAMP": str(stamp_us),
        "__MONOTONIC_TIMESTAMP": str(1_000_000 + number),
        "_BOOT_ID": BOOT_ID,
    }
    for name, value in {**base, **fields}.items():
        data = value.encode() if isinstance(value, str) else value
        if b"\n" in data or not all(32 <= byte < 127 or byte >= 128 or byte == 9 for byte in data):
            out += name.encode() + b"\n" + struct.pack("<Q", len(data)) + data + b"\n"
        else:
            out += name.encode() + b"=" + data + b"\n"
    return bytes(out) + b"\n"


def make_journal(
    path: Path, entries: Sequence[Mapping[str, str | bytes]], *, first_us: int = 1_765_000_000_000_000
) -> Path:
    """A journal file at ``path`` (its name ends in ``.journal``; an existing one is appended
    to), the entries a millisecond apart from ``first_us``."""
    program = journal_remote()
    export = path.with_suffix(".export")
    export.write_bytes(b"".join(export_entry(e, first_us + i * 1000, i) for i, e in enumerate(entries)))
    done = subprocess.run([program, f"--output={path}", str(export)], capture_output=True, timeout=60)
    assert done.returncode == 0, done.stderr.decode(errors="replace")
    export.unlink()
    return path
