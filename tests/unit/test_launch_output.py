"""A launch's terminal read as records (``model/formats/launch_output.py``), its copies merged
with /rosout's (``LiveRepeats``), and the command run in a group of its own and stopped as a
terminal's Ctrl+C would (``LaunchedCommand``, on real processes): no ROS here."""

from __future__ import annotations

import os
import sys
import textwrap
import time
from pathlib import Path

import pytest

from console_tui.model.formats.launch_output import (
    UNATTRIBUTED,
    DeathAttribution,
    LaunchLines,
    clean_line,
    live_records,
)
from console_tui.model.store.record import LogRecord
from console_tui.sources.files.repeats import SIDE_LAUNCH, SIDE_NODE, SIDE_ROSOUT, LiveRepeats
from console_tui.sources.launch import launched_command
from console_tui.sources.launch.launch_source import launcher_name, ros_of
from console_tui.sources.launch.launched_command import LaunchedCommand, LaunchFailed, group_members
from console_tui.sources.launch.node_outputs import run_folder

DATA = Path(__file__).parent.parent / "data" / "launch_output"


class Clock:
    """Nanoseconds that move on by a millisecond a read."""

    def __init__(self) -> None:
        self.now = 1_765_015_200_000_000_000

    def __call__(self) -> int:
        self.now += 1_000_000
        return self.now


def records_of(name: str, *, pause_after: tuple[str, ...] = ()) -> list[LogRecord]:
    """A fixture's lines read live, a pause after each line that starts with ``pause_after``."""
    lines: list[str | None] = []
    for raw in (DATA / name).read_text().splitlines():
        line = clean_line(raw)
        lines.append(line)
        if line.startswith(pause_after):
            lines.append(None)
    lines.append(None)
    return list(live_records(lines, Clock(), source="launch", parser=LaunchLines()))


def test_ros2_launch_output_as_records_of_its_processes():
    records = records_of("ros2_launch_screen.txt")
    shown = [(r.level, r.node, r.msg.splitlines()[0]) for r in records]
    assert shown[:5] == [
        (20, "launch", "All log files can be found below /home/robot/.ros/log/2026-12-06-10-00-00-123456-robot-4242"),
        (20, "launch", "Default logging verbosity is set to INFO"),
        (20, "talker-1", "process started with pid [4243]"),
        (20, "listener-2", "process started with pid [4245]"),
        (20, "camera_driver-3", "process started with pid [4247]"),
    ]
    talker = records[5]
    assert (talker.node, talker.msg, talker.stamp_ns) == ("talker", "Publishing: 'Hello World: 1'", 1765015200501234567)
    # a printed line, then a node's coloured log line: the colour gone, the record its logger's
    assert (records[7].node, records[7].msg) == ("camera_driver-3", "opening /dev/video0")
    assert (records[8].level, records[8].node, records[8].msg) == (
        30,
        "camera.driver",
        "no calibration file, using defaults",
    )
    traceback = next(r for r in records if r.msg.startswith("Traceback"))
    assert traceback.level == 40 and traceback.node == "camera_driver-3"
    assert traceback.msg.splitlines()[-1] == "RuntimeError: cannot open /dev/video0" and traceback.msg.count("\n") == 5
    deaths = [r for r in records if "process has died" in r.msg]
    assert [(d.level, d.node) for d in deaths] == [(40, "camera_driver-3"), (40, "listener-2")]
    assert ("launch", 30, "user interrupted with ctrl-c (SIGINT)") in [(r.node, r.level, r.msg) for r in records]
    assert (40, "listener-2") in [(r.level, r.node) for r in records if "escalating to 'SIGTERM'" in r.msg]
    assert not any("\x1b" in r.msg for r in records)


def test_roslaunch_output_recorded_here():
    """Debian's roslaunch 1.15.15, recorded through console-tui run's own reader."""
    records = records_of("roslaunch_two_nodes.txt", pause_after=("[WARN]",))
    by_text = {r.msg.splitlines()[0]: r for r in records}
    assert not any("\x1b" in r.msg or "two_nodes.launch http" in r.msg for r in records), "titles and colours gone"
    summary = by_text["SUMMARY"]
    assert summary.node == UNATTRIBUTED and "printer (console_tui_launch_test/printer.py)" in summary.msg
    assert by_text["process[printer-2]: started with pid [16339]"].node == "/printer"
    assert by_text["process[master]: started with pid [16323]"].node == "master"
    warning = by_text["about to die"]
    assert (warning.level, warning.node, warning.stamp_ns) == (30, UNATTRIBUTED, 1796590110334424000)
    traceback = by_text["Traceback (most recent call last):"]
    assert traceback.level == 40 and traceback.msg.endswith("ValueError: the dier gave up")
    death = next(r for r in records if "process has died" in r.msg)
    assert (death.level, death.node) == (40, "/dier")
    assert death.msg.splitlines()[-1].startswith("log file: /home/robot/.ros/log/"), "its log file line with it"
    assert [r.node for r in records if r.msg.endswith("killing on exit")] == ["/printer", "/rosout", "master"]
    # the traceback of no known process is the process's whose death comes right after it
    attribution = DeathAttribution()
    out: list[LogRecord] = []
    for number, record in enumerate(records):
        out += attribution.take(record, number)
    out += attribution.due(10**12)
    assert next(r for r in out if r.msg.startswith("Traceback")).node == "/dier"
    assert [r.msg for r in out] == [r.msg for r in records], "nothing lost, in order"


def test_a_traceback_without_a_death_goes_on_unattributed():
    attribution = DeathAttribution(wait_ns=100)
    traceback = LogRecord(1, 40, UNATTRIBUTED, "Traceback (most recent call last):\n  ...")
    other = LogRecord(2, 20, "/printer", "printed")
    assert attribution.take(traceback, 0) == [] and attribution.take(other, 10) == [other]
    assert attribution.due(50) == [] and attribution.due(100) == [traceback]
    assert traceback.node == UNATTRIBUTED


def test_the_launchers_and_their_ros():
    assert ros_of(["roslaunch", "pkg", "a.launch"]) == 1 and ros_of(["/opt/ros/bin/ros2", "launch"]) == 2
    assert ros_of(["./my_launch.sh"]) is None and ros_of([]) is None
    assert launcher_name(["ros2", "launch", "p", "f"]) == "launch" and launcher_name(["roslaunch"]) == "roslaunch"
    assert run_folder("... logging to /home/r/.ros/log/abc/roslaunch-host-42.log") == Path("/home/r/.ros/log/abc")
    assert run_folder("logging to nothing") is None
    assert clean_line("^C[WARNING] [launch]: x\r") == "[WARNING] [launch]: x"


def rec(stamp: int, node: str, msg: str, source: str, level: int = 20) -> LogRecord:
    return LogRecord(stamp, level, node, msg, source=source)


def test_live_copies_of_a_message_are_one_record_whatever_their_arrival():
    repeats = LiveRepeats(hold_ns=1000, tolerance_ns=20)
    repeats.add([rec(100, UNATTRIBUTED, "about to die", "roslaunch", 30)], SIDE_LAUNCH, now_ns=0)
    repeats.add([rec(105, "/printer", "logged 0", "printer-2-stdout.log")], SIDE_NODE, now_ns=10)
    assert repeats.due(500) == [], "each waits for its copies"
    repeats.add([rec(101, "/dier", "about to die", "/rosout_agg", 30)], SIDE_ROSOUT, now_ns=600)
    repeats.add([rec(104, "/printer", "logged 0", "/rosout_agg")], SIDE_ROSOUT, now_ns=600)
    out = repeats.due(1010)
    assert [(r.node, r.msg, r.source, r.stamp_ns) for r in out] == [
        ("/dier", "about to die", "/rosout_agg + roslaunch", 101),
        ("/printer", "logged 0", "/rosout_agg + printer-2-stdout.log", 104),
    ], "the /rosout copy kept, named for both, in the place of the first copy to come"
    assert repeats.merged == 2


def test_live_messages_logged_twice_or_far_apart_stay_two():
    repeats = LiveRepeats(hold_ns=0, tolerance_ns=20)
    repeats.add([rec(100, "/a", "tick", "/rosout"), rec(100, "/a", "tick", "/rosout")], SIDE_ROSOUT, 0)
    repeats.add([rec(100, "/a", "tick", "roslaunch")], SIDE_LAUNCH, 0)
    repeats.add([rec(500, "/a", "tick", "roslaunch"), rec(100, "/b", "tick", "b-1-stdout.log")], SIDE_LAUNCH, 0)
    out = repeats.flush()
    assert [(r.node, r.stamp_ns, r.source) for r in out] == [
        ("/a", 100, "/rosout + roslaunch"),
        ("/a", 100, "/rosout"),
        ("/a", 500, "roslaunch"),
        ("/b", 100, "b-1-stdout.log"),
    ]


def script(tmp_path: Path, body: str) -> list[str]:
    path = tmp_path / "launch.py"
    path.write_text(textwrap.dedent(body))
    return [sys.executable, str(path)]


def test_the_command_writes_to_a_terminal_and_long_lines_are_cut(tmp_path, monkeypatch):
    monkeypatch.setattr(launched_command, "MAX_LINE_CHARS", 100)
    command = LaunchedCommand(
        script(
            tmp_path,
            """
            import os, sys
            print("stdout is a terminal" if os.isatty(1) else "stdout is a pipe")
            print("PYTHONUNBUFFERED=" + os.environ.get("PYTHONUNBUFFERED", ""))
            print("x" * 500)
            print("to stderr", file=sys.stderr)
            sys.stdout.write("no line end")
            """,
        ),
        env={k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"},
    )
    lines = [line for line in command.lines(0.05) if line is not None]
    assert command.stop() == 0
    assert lines == [
        "stdout is a terminal",
        "PYTHONUNBUFFERED=1",
        "x" * 100 + " … [cut: the line went on]",
        "to stderr",
        "no line end",
    ]


def test_stop_is_sigint_to_the_group_then_escalation_and_nothing_is_left(tmp_path, monkeypatch):
    """A launch whose child ignores SIGINT and SIGTERM (as a hung node does): SIGINT to the
    whole group (the launch ends on it), then SIGTERM, then SIGKILL for what is left."""
    monkeypatch.setattr(launched_command, "SIGINT_WAIT_S", 0.5)
    monkeypatch.setattr(launched_command, "SIGTERM_WAIT_S", 0.5)
    marker = tmp_path / "child.pid"
    command = LaunchedCommand(
        script(
            tmp_path,
            f"""
            import signal, subprocess, sys, time
            child = subprocess.Popen([sys.executable, "-c", (
                "import os, signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN); "
                "signal.signal(signal.SIGTERM, signal.SIG_IGN); "
                "open({str(marker)!r}, 'w').write(str(os.getpid())); time.sleep(600)")])
            print("launched", flush=True)
            try:
                time.sleep(600)
            except KeyboardInterrupt:
                print("interrupted", flush=True)
            """,
        )
    )
    lines = command.lines(0.05)
    assert next(line for line in lines if line is not None) == "launched"
    while not marker.exists() or not marker.read_text():
        time.sleep(0.02)
    child = int(marker.read_text())
    assert child in group_members(command.pid)
    said: list[str] = []
    code = command.stop(said.append)
    rest = [line for line in lines if line is not None]
    assert rest == ["interrupted"] and code == 0
    assert group_members(command.pid) == [], "the child too: it was of the group"
    assert said == [
        "the launch still runs 0.5 s after SIGINT: SIGTERM to its processes",
        "the launch still runs 0.5 s after SIGTERM: SIGKILL to its processes",
    ]


def test_a_command_that_cannot_start_says_why(tmp_path):
    with pytest.raises(LaunchFailed, match="no-such-launcher"):
        LaunchedCommand([str(tmp_path / "no-such-launcher")])
