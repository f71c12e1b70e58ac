"""Hostile command lines (issue 17): an endless ``--timeout inf`` is refused up front, with a
message and status 2, instead of waiting for ever and ending in an OverflowError traceback."""

from __future__ import annotations

import subprocess
import sys

import pytest


@pytest.mark.parametrize(
    "args",
    [
        ["get", "talker", "--timeout", "inf"],
        ["get", "talker", "--wait", "Infinity"],
        ["set", "talker", "debug", "--for", "inf"],
        ["set", "talker", "debug", "--timeout", "1e300"],
        ["list", "--wait", "nan"],
    ],
)
def test_endless_seconds_are_refused(args):
    result = subprocess.run(
        [sys.executable, "-m", "console_tui", "loggers", *args], capture_output=True, text=True, timeout=60
    )
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert "must be" in result.stderr
