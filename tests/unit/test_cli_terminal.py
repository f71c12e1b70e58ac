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
