"""``console-tui`` without a terminal (nohup, cron, systemd, a pipe): it says so and exits 2 at
once, instead of reading an empty standard input in a loop with a core busy for ever."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

ENV = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[2])}
DATA = Path(__file__).parents[1] / "data" / "rqt_console_ros2.csv"


def run_without_terminal(args: list[str], *, stdin_null: bool = True) -> tuple[int, bytes, bytes, float]:
    """Run ``console-tui ARGS`` with standard input from /dev/null (or a pipe), output to pipes;
    returns the exit status, stdout, stderr and the CPU seconds the process used."""
    process = subprocess.Popen(
        [sys.executable, "-m", "console_tui", *args],
        stdin=subprocess.DEVNULL if stdin_null else subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=ENV,
    )
    if process.stdin is not None:
        process.stdin.close()
    deadline = time.monotonic() + 120  # generous: a process that never ends fails here
    while process.poll() is None and time.monotonic() < deadline:
        try:
            process.wait(1)
        except subprocess.TimeoutExpired:
            pass
    if process.returncode is None:
        process.kill()
        process.wait()
        pytest.fail("console-tui without a terminal did not end")
    assert process.stdout is not None and process.stderr is not None
    out, err = process.stdout.read(), process.stderr.read()
    return process.returncode, out, err, _cpu_of_children()


def _cpu_of_children() -> float:
    import resource

    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


@pytest.mark.parametrize(
    "args, stdin_null",
    [([str(DATA)], True), ([str(DATA)], False), (["--demo"], True)],
    ids=["file-devnull", "file-closed-pipe", "demo-devnull"],
)
def test_without_a_terminal_it_says_so_and_exits(args, stdin_null):
    before = _cpu_of_children()
    status, out, err, after = run_without_terminal(args, stdin_null=stdin_null)
    assert status == 2
    assert out == b""
    text = err.decode()
    assert text.startswith("console-tui: not a terminal:")
    assert "console-tui tail" in text
    assert "Traceback" not in text
    # A bound on the CPU the process used (never a wall-clock assertion): the spinning app
    # used a core for as long as it ran; this one parses its arguments and ends.
    assert after - before < 30


def test_help_and_version_need_no_terminal():
    status, out, err, _ = run_without_terminal(["--version"])
    assert status == 0 and out.startswith(b"console-tui ") and err == b""


def test_another_driver_needs_no_terminal(monkeypatch):
    """``console-tui serve`` runs each browser's console with Textual's web driver, on pipes."""
    from console_tui.cli import on_a_terminal

    monkeypatch.setenv("TEXTUAL_DRIVER", "textual.drivers.web_driver:WebDriver")
    assert on_a_terminal()


def test_a_terminal_that_goes_away_without_a_hangup_signal_ends_it():
    """An SSH session dropping while its shell ignores SIGHUP: the kernel signals only the
    session leader, so the console gets no SIGHUP, and reads from the terminal return nothing
    at once. It ends, as on SIGHUP, instead of spinning a core for ever."""
    import pty
    import select
    import signal

    console = str(Path(sys.executable).parent / "console-tui")
    pid, fd = pty.fork()
    if pid == 0:  # the child: a shell that ignores SIGHUP, the console its child (not a session leader)
        os.execve("/bin/sh", ["sh", "-c", 'trap "" HUP; "$0" "$1"; exit 0', console, str(DATA)], ENV)
    try:
        seen = b""
        deadline = time.monotonic() + 40
        while b"FOLLOW" not in seen and time.monotonic() < deadline:
            if select.select([fd], [], [], 0.2)[0]:
                try:
                    seen += os.read(fd, 65536)
                except OSError:
                    break
        assert b"FOLLOW" in seen, seen[-2000:]
        os.close(fd)  # the terminal goes away; no SIGHUP reaches the console
        deadline = time.monotonic() + 60  # generous (within pytest's timeout): a spinning console never ends
        while time.monotonic() < deadline:
            done, status, usage = os.wait4(pid, os.WNOHANG)
            if done:
                break
            time.sleep(0.2)
        else:
            pytest.fail("the console did not end when its terminal went away")
    finally:
        try:
            reaped = os.waitpid(pid, os.WNOHANG)[0]
        except ChildProcessError:  # reaped above
            reaped = pid
        if not reaped:  # the shell and the console, ended
            os.killpg(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0
    assert usage.ru_utime + usage.ru_stime < 60  # the shell and the console: no core spun
