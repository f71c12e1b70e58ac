"""Start-up and quit benchmark: from launching ``console-tui`` to its first frame on a
terminal, to the first live row of a node that was publishing before it started, and from
pressing ``q`` to the app and every process it started being gone.

    .venv/bin/python benchmarks/startup.py [--runs 5] [--against CHECKOUT] [-- ARGS...]

Runs the real command in a pseudo-terminal (160x48), as a user's shell would, and reads
its output until the table's header row has been drawn (the first frame); two seconds later
(the intake process and demo nodes are up by then) it types ``q`` and waits for the command
to end and for its child processes (the intake process, demo nodes) to be gone. Each run has a
ROS domain of its own and loopback-only discovery.

The first live row: a real rclpy node (``tests/nodes/talker.py``, a process of its own) is
started on the run's domain and logs a line before ``console-tui`` (live) is launched, and
every 0.2 s after; the time is from the launch until that line is on the screen.

Beside each time, the CPU (user + system) the app's process had used by then, which a
loaded machine inflates far less than the wall-clock time; for the first live row, the
app's and its child processes' (the intake process) together. Python's bytecode caches of
console_tui are written first (as an installed package has them), else
``PYTHONDONTWRITEBYTECODE`` would make every run compile the app's modules. Prints a table
with the targets beside the figures.
"""

from __future__ import annotations

import argparse
import compileall
import fcntl
import json
import os
import pty
import select
import signal
import statistics
import struct
import subprocess
import sys
import termios
import time
from pathlib import Path

from _report import machine_line

TARGET_S = 0.5
LIVE_ROW_TARGET_S = 1.0
QUIT_TARGET_S = 1.0
ROOT = Path(__file__).resolve().parent.parent
TALKER = ROOT / "tests" / "nodes" / "talker.py"
#: The line the publishing node logs before the console starts, looked for on the screen.
MARKER = "first-live-row"
_TICK_S = os.sysconf("SC_CLK_TCK")


def _children(pid: int) -> set[int]:
    found: set[int] = set()
    try:
        for task in os.listdir(f"/proc/{pid}/task"):
            with open(f"/proc/{pid}/task/{task}/children", encoding="ascii") as children:
                found.update(int(child) for child in children.read().split())
    except OSError:
        pass
    return found


def _cpu(pid: int, *, children: bool = False) -> float:
    """Seconds of CPU (user + system) ``pid`` has used, and with ``children`` its living
    child processes' too."""
    total = 0.0
    for one in [pid, *(_children(pid) if children else ())]:
        try:
            with open(f"/proc/{one}/stat", encoding="ascii") as stat:
                fields = stat.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        total += (int(fields[11]) + int(fields[12])) / _TICK_S
    return total


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


class Run:
    """What one launch measured: seconds from the launch and CPU seconds used by then."""

    def __init__(self) -> None:
        nan = float("nan")
        self.frame = self.frame_cpu = self.row = self.row_cpu = self.quit = nan


def launch(argv: list[str], domain: int, *, marker: str = "", timeout: float = 20.0, code: str = "") -> Run:
    """Launch ``argv`` in a pseudo-terminal: its first frame, the first time ``marker`` is on
    the screen (when given), and from ``q`` until the command and its children are gone.
    ``code``: a checkout whose ``console_tui`` runs instead of this one's (``PYTHONPATH``)."""
    env = {
        **os.environ,
        **({"PYTHONPATH": code} if code else {}),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "ROS_DOMAIN_ID": str(domain),
        "TERM": "xterm-256color",
    }
    run = Run()
    started = time.perf_counter()
    pid, fd = pty.fork()
    if pid == 0:
        os.execvpe(argv[0], argv, env)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", 48, 160, 0, 0))
    seen = b""
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
            now = time.perf_counter() - started
            if run.frame != run.frame and b"Message" in seen and b"Node" in seen:
                run.frame, run.frame_cpu = now, _cpu(pid)
            if marker and run.row != run.row and marker.encode() in seen:
                run.row, run.row_cpu = now, _cpu(pid, children=True)
            if run.frame == run.frame and (not marker or run.row == run.row):
                break
        run.quit = quit_with_q(pid, fd)
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
    return run


def with_publisher(argv: list[str], domain: int, code: str = "") -> Run:
    """``launch`` while a real node on ``domain`` publishes: it logged ``MARKER`` before the launch."""
    env = {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST", "ROS_DOMAIN_ID": str(domain)}
    talker = subprocess.Popen(
        [sys.executable, str(TALKER), "--name", "startup_talker"],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        env=env,
        text=True,
    )
    assert talker.stdin is not None and talker.stdout is not None
    try:
        if json.loads(talker.stdout.readline()).get("event") != "ready":
            raise SystemExit("the talker did not start")
        for command in ({"cmd": "log", "level": "info", "msg": MARKER}, {"cmd": "periodic", "period": 0.2}):
            talker.stdin.write(json.dumps(command) + "\n")
            talker.stdin.flush()
            talker.stdout.readline()
        return launch(argv, domain, marker=MARKER, code=code)
    finally:
        talker.stdin.close()
        try:
            talker.wait(5)
        except subprocess.TimeoutExpired:
            talker.kill()
            talker.wait()


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


def _seconds(values: list[float]) -> str:
    return f"{statistics.median(values):.2f} s ({min(values):.2f}-{max(values):.2f})"


def _verdict(value: float, target: float) -> str:
    return "met" if value <= target else f"MISSED by {value - target:.2f} s"


def write_bytecode(against: Path | None = None) -> None:
    """Compile console_tui's modules (and ``against``'s) into their caches, as installing the
    package does."""
    import console_tui

    compileall.compile_dir(Path(console_tui.__file__).parent, quiet=1)
    if against is not None:
        compileall.compile_dir(against / "console_tui", quiet=1)


def _frame_row(label: str, runs: list[Run]) -> str:
    frames = [run.frame for run in runs]
    worst_quit = max(run.quit for run in runs)
    return (
        f"| `{label}` | {len(runs)} | {_seconds(frames)} | {statistics.median(run.frame_cpu for run in runs):.2f} s "
        f"| {TARGET_S} s | {_verdict(statistics.median(frames), TARGET_S)} | {worst_quit:.2f} s | {QUIT_TARGET_S} s "
        f"| {'met' if worst_quit <= QUIT_TARGET_S else 'MISSED'} |"
    )


def _row_row(label: str, runs: list[Run]) -> str:
    rows = [run.row for run in runs]
    return (
        f"| `{label}` | {len(rows)} | {_seconds(rows)} | {statistics.median(run.row_cpu for run in runs):.2f} s "
        f"| {LIVE_ROW_TARGET_S} s | {_verdict(statistics.median(rows), LIVE_ROW_TARGET_S)} |"
    )


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--domain", type=int, default=60, help="the first of the ten ROS domains the runs use")
    parser.add_argument(
        "--against",
        type=Path,
        help="another checkout of console-tui (the folder holding console_tui/): each run is followed by one "
        "of that code (PYTHONPATH), in turns, and its rows are printed beside (marked 'against'); the "
        "machine's speed drifts by a fifth within an hour here, so compare changes this way",
    )
    parser.add_argument("args", nargs="*", help="arguments for console-tui (after --)")
    args = parser.parse_args()
    against = str(args.against.resolve()) if args.against else ""
    write_bytecode(args.against)
    command = str(Path(sys.executable).parent / "console-tui")
    cases = [([], False), (["--demo"], False), ([], True)]
    if args.args:  # these arguments, and with a node publishing unless the demo's domain is its own
        cases = [(args.args, False), *([] if "--demo" in args.args else [(args.args, True)])]
    print(machine_line() + "\n")
    print(
        "| command | runs | first frame, median (min-max) | CPU by then | target | | quit after q, worst | target | |"
    )
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    live: list[tuple[str, list[Run]]] = []
    for n, (case, publisher) in enumerate(cases):
        measure = with_publisher if publisher else launch
        runs: list[Run] = []
        others: list[Run] = []
        for run in range(args.runs):
            domain = args.domain + (n * args.runs + run) % 10
            runs.append(measure([command, *case], domain))
            if against:
                others.append(measure([command, *case], domain, code=against))
        label = " ".join(["console-tui", *case])
        if publisher:
            live += [(label, runs), *([(label + " (against)", others)] if others else [])]
        label += " (a node publishing)" if publisher else ""
        print(_frame_row(label, runs))
        if others:
            print(_frame_row(label + " (against)", others))
    if live:
        print(
            "\n| first live row of a node already publishing | runs | median (min-max) | CPU by then, app and intake | target | |"
        )
        print("| --- | --- | --- | --- | --- | --- |")
        for label, runs in live:
            print(_row_row(label, runs))
    if against:
        print(f"\n(against: {against})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
