"""``console-tui rosout`` (the rosout aggregator) in a process of its own, for tests."""

from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

from console_tui.sources.files import load_records, open_files

from support.rosproc import wait_until


class Aggregator:
    """``console-tui rosout`` in a process of its own, writing into ``log_dir``."""

    def __init__(self, env: dict[str, str], log_dir: Path, *args: str) -> None:
        self.log_dir = log_dir
        self.path = log_dir / "rosout.log"
        self.process = subprocess.Popen(
            [sys.executable, "-m", "console_tui", "rosout", "--log-dir", str(log_dir), *args],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=env,
        )

    def records(self, *paths: Path) -> list:
        files, failures = open_files([str(p) for p in (paths or (self.path,))])
        assert failures == []
        try:
            records = [r for batch in load_records(files) for r in batch]
            assert [str(p) for f in files for p in f.problems] == []
        finally:
            for f in files:
                f.close()
        return records

    def written(self) -> bytes:
        """All it has written so far: ``rosout.log`` and the rotated files before it. A rotation
        renames ``rosout.log`` before it opens a new one, so for a moment a file may be missing."""
        out = []
        for path in sorted(self.log_dir.glob("rosout.log*"), reverse=True):
            try:
                out.append(path.read_bytes())
            except FileNotFoundError:
                pass
        return b"".join(out)

    def wait_running(self, timeout: float = 30) -> None:
        """Until its own start-up message came back through /rosout into rosout.log."""
        assert wait_until(lambda: b"republishing /rosout" in self.written(), timeout), self.stop_and_read()

    def stop(self, sig: int = signal.SIGINT, timeout: float = 15) -> int:
        if self.process.poll() is None:
            self.process.send_signal(sig)
            try:
                self.process.wait(timeout)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        return self.process.returncode

    def stop_and_read(self) -> str:
        self.stop()
        return self.process.stderr.read().decode(errors="replace")[-3000:]
