"""Start-up benchmark: time from launching ``console-tui`` to its first frame on a terminal.

    .venv/bin/python benchmarks/startup.py [--runs 5] [-- ARGS...]

Runs the real command in a pseudo-terminal (160x48), as a user's shell would, and reads
its output until the table's header row has been drawn. Each run has a ROS domain of its
own and loopback-only discovery. Prints a table with the target beside the figures.
"""

from __future__ import annotations

import argparse
import fcntl
import os
import pty
import select
import signal
import statistics
import struct
import sys
import termios
import time
from pathlib import Path

from _report import machine_line

TARGET_S = 1.5
ROOT = Path(__file__).resolve().parent.parent


def first_frame(argv: list[str], domain: int, timeout: float = 20.0) -> float:
    env = {
        **os.environ,
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "ROS_DOMAIN_ID": str(domain),
        "TERM": "xterm-256color",
    }
    started = time.perf_counter()
    pid, fd = pty.fork()
    if pid == 0:
        os.execvpe(argv[0], argv, env)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 48, 160, 0, 0))
    seen = b""
    elapsed = float("nan")
    try:
        while time.perf_counter() - started < timeout:
            ready, _, _ = select.select([fd], [], [], 0.05)
            if not ready:
                continue
            try:
                chunk = os.read(fd, 65536)
            except OSError:
                break
            seen += chunk
            if b"Message" in seen and b"Node" in seen:
                elapsed = time.perf_counter() - started
                break
    finally:
        os.kill(pid, signal.SIGTERM)
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline:
            done, _ = os.waitpid(pid, os.WNOHANG)
            if done:
                break
            time.sleep(0.05)
        else:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        os.close(fd)
    return elapsed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("args", nargs="*", help="arguments for console-tui (after --)")
    args = parser.parse_args()
    command = str(Path(sys.executable).parent / "console-tui")
    cases = [args.args] if args.args else [[], ["--demo"]]
    print(machine_line() + "\n")
    print("| command | runs | median | min | max | target | |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for n, case in enumerate(cases):
        times = [first_frame([command, *case], domain=60 + n * 10 + run % 10) for run in range(args.runs)]
        median = statistics.median(times)
        verdict = "met" if median <= TARGET_S else f"MISSED by {median - TARGET_S:.2f} s"
        label = " ".join(["console-tui", *case])
        print(
            f"| `{label}` | {len(times)} | {median:.2f} s | {min(times):.2f} s | {max(times):.2f} s | {TARGET_S} s | {verdict} |"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
