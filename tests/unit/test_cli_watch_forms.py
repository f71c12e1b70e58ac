"""``ros2 log watch``'s options on ``console-tui tail`` (and ``console-tui watch``, its alias):
``--level/--logger/--regex/--no-timestamp/--no-color`` filter and print as ``ros2 log watch``
does. Files only, no ROS needed."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from console_tui.model.formats.rosout_log import ROS2_HEADER, rosout_log_text
from console_tui.model.store.record import LogRecord

ENV = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[2])}
ENV.pop("NO_COLOR", None)
ENV.pop("RCUTILS_CONSOLE_OUTPUT_FORMAT", None)

T0 = 1_700_000_000_000_000_000
RECORDS = [
    LogRecord(T0, 20, "talker", "hello 1"),
    LogRecord(T0 + 1, 30, "talker", "slow/down 2"),
    LogRecord(T0 + 2, 40, "nav.planner", "failed 3"),
    LogRecord(T0 + 3, 10, "nav.planner", "detail 4"),
]


@pytest.fixture
def log(tmp_path: Path) -> str:
    path = tmp_path / "rosout.log"
    path.write_text(ROS2_HEADER + "".join(rosout_log_text(r) for r in RECORDS))
    return str(path)


def run(verb: str, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "console_tui", verb, *args], capture_output=True, text=True, env=ENV, timeout=60
    )


def messages(result: subprocess.CompletedProcess) -> list[str]:
    assert result.returncode == 0, result.stderr
    return [line.rsplit(": ", 1)[1] for line in result.stdout.splitlines()]


def test_level_logger_and_regex_filter_as_ros2_log_watch_does(log):
    assert messages(run("tail", log, "--level", "WARN")) == ["slow/down 2", "failed 3"]
    assert messages(run("tail", log, "--logger", "nav.planner")) == ["failed 3", "detail 4"]
    assert messages(run("tail", log, "--logger", "nav.*", "--level", "error")) == ["failed 3"]
    assert messages(run("tail", log, "--regex", r"^(hello|slow/down) \d")) == ["hello 1", "slow/down 2"]
    # Together with the app's own query: both hold.
    assert messages(run("tail", log, "--level", "info", "--query=-node:talker")) == ["failed 3"]


def test_watch_is_tail(log):
    assert run("watch", log, "--level", "error", "--no-timestamp").stdout == "[ERROR] [nav.planner]: failed 3\n"


def test_no_timestamp_and_no_color(log):
    result = run("tail", log, "--no-timestamp", "--no-color", "--level", "warn")
    assert result.stdout == "[WARN] [talker]: slow/down 2\n[ERROR] [nav.planner]: failed 3\n"


@pytest.mark.parametrize(
    ("args", "said"),
    [
        (["--level", "loud"], "--level: unknown level 'loud'"),
        (["--regex", "(open"], "--regex: not a regular expression"),
        (["--logger", "a b"], "--logger: not a logger name or glob"),
        (["--no-timestamp", "--json"], "--no-timestamp: only with the default line"),
        (["--no-color", "--color", "always"], "not allowed with argument"),
    ],
)
def test_bad_values_exit_2_naming_the_option(log, args, said):
    result = run("tail", log, *args)
    assert result.returncode == 2 and said in result.stderr and result.stdout == ""
