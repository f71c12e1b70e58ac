"""Start-up and quit benchmark: from launching ``console-tui`` to its first frame on a
terminal, and from pressing ``q`` to the app and every process it started being gone.

    .venv/bin/python benchmarks/startup.py [--runs 5] [-- ARGS...]

Runs the real command in a pseudo-terminal (160x48), as a user's shell would, and reads
its output until the table's header row has been drawn; two seconds later (the intake
process and demo nodes are up by then) it types ``q`` and waits for the command to end
and for its child processes (the intake process, demo nodes) to be gone. Each run has a
ROS domain of its own and loopback-only discovery. Prints a table with the targets
beside the figures.
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
QUIT_TARGET_S = 1.0
ROOT = Path(__file__).resolve().parent.parent


def _children(pid: int) -> set[int]:
    found: set[int] = set()
    try:
        for task in os.listdir(f"/proc/{pid}/task"):
            with open(f"/proc/{pid}/task/{task}/children", encoding="ascii") as children:
                found.update(int(child) for child in children.read().split())
    except OSError:
        pass
    return found


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def first_frame(argv: list[str], domain: int, timeout: float = 20.0) -> tuple[float, float]:
    """Seconds to the first frame, and from ``q`` until the command and its children are gone."""
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
        quit_seconds = quit_with_q(pid, fd)
    finally:
        try:
            os.kill(pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline:
            try:
                done, _ = os.waitpid(pid, os.WNOHANG)
            except ChildProcessError:
                break
            if done:
                break
            time.sleep(0.05)
        else:
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
        os.close(fd)
    return elapsed, quit_seconds


def quit_with_q(pid: int, fd: int, wait: float = 2.0, timeout: float = 10.0) -> float:
    """Type ``q`` after ``wait`` seconds; seconds until ``pid`` and the children it had are gone."""
    deadline = time.monotonic() + wait
    while time.monotonic() < deadline:
        if select.select([fd], [], [], 0.05)[0]:
            os.read(fd, 65536)
    children = _children(pid)
    pressed = time.perf_counter()
    os.write(fd, b"q")
    ended = False
    while time.perf_counter() - pressed < timeout:
        if not ended and os.waitpid(pid, os.WNOHANG)[0]:
            ended = True
        if ended and not any(_alive(child) for child in children):
            return time.perf_counter() - pressed
        if select.select([fd], [], [], 0.01)[0]:
            try:
                os.read(fd, 65536)
            except OSError:
                pass
    return float("nan")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--domain", type=int, default=60, help="the first of the ROS domains the runs use")
    parser.add_argument("args", nargs="*", help="arguments for console-tui (after --)")
    args = parser.parse_args()
    command = str(Path(sys.executable).parent / "console-tui")
    cases = [args.args] if args.args else [[], ["--demo"]]
    print(machine_line() + "\n")
    print("| command | runs | first frame, median | min | max | target | | quit after q, worst | target | |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for n, case in enumerate(cases):
        runs = [first_frame([command, *case], domain=args.domain + n * 10 + run % 10) for run in range(args.runs)]
        times = [first for first, _ in runs]
        quits = [quit for _, quit in runs]
        median = statistics.median(times)
        verdict = "met" if median <= TARGET_S else f"MISSED by {median - TARGET_S:.2f} s"
        worst_quit = max(quits)
        quit_verdict = "met" if worst_quit <= QUIT_TARGET_S else "MISSED"
        label = " ".join(["console-tui", *case])
        print(
            f"| `{label}` | {len(times)} | {median:.2f} s | {min(times):.2f} s | {max(times):.2f} s | {TARGET_S} s "
            f"| {verdict} | {worst_quit:.2f} s | {QUIT_TARGET_S} s | {quit_verdict} |"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
