"""Real journal files, made by Debian's systemd-journal-remote from exported entries, read back
by ``convert``, ``tail`` and ``tail -f`` (the files themselves and ``journal:PATH``): every
field the issue names, rcl_logging_syslog's entries among them; a fleet's directory; the
same messages in a rosout.log and a robot's journal, one row each. The live journal of this
machine where it has one."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest

from console_tui.model.formats.rosout_log import ROS2_HEADER
from console_tui.sources.journal.journalctl import local_journal_problem

from support.journal_files import journal_remote, make_journal
from support.run_main import run_main
from support.tail_process import TailProcess
from support.ui import screen_text, until

#: What a robot's journal holds: a unit's stdout, a node logging through rcl_logging_syslog
#: (its executable the identifier, LOCAL1, the console line as the message), python-systemd's
#: structured entry, a kernel line, a multi-line traceback, bytes that are not UTF-8.
ENTRIES = [
    {"PRIORITY": "6", "SYSLOG_IDENTIFIER": "nav_bringup", "_SYSTEMD_UNIT": "nav.service", "MESSAGE": "starting"},
    {
        "PRIORITY": "4",
        "SYSLOG_IDENTIFIER": "planner_node",
        "SYSLOG_FACILITY": "17",
        "SYSLOG_PID": "4242",
        "_SYSTEMD_UNIT": "nav.service",
        "MESSAGE": "[WARN] [1765000000.001000007] [nav.planner]: no path from (0, 0)",
    },
    {
        "PRIORITY": "1",
        "SYSLOG_IDENTIFIER": "planner_node",
        "SYSLOG_FACILITY": "17",
        "MESSAGE": "[FATAL] [1765000000.002000000] [nav.planner]: giving up",
    },
    {
        "PRIORITY": "3",
        "SYSLOG_IDENTIFIER": "battery.py",
        "CODE_FILE": "/opt/robot/battery.py",
        "CODE_FUNC": "check",
        "CODE_LINE": "88",
        "MESSAGE": "battery low: 9%",
    },
    {"PRIORITY": "2", "SYSLOG_IDENTIFIER": "kernel", "MESSAGE": "usb 1-1: device descriptor read/64, error -71"},
    {
        "PRIORITY": "3",
        "SYSLOG_IDENTIFIER": "arm_driver",
        "MESSAGE": 'Traceback (most recent call last):\n  File "arm.py", line 3\nValueError: bad joint',
    },
    {"PRIORITY": "7", "_COMM": "camera", "MESSAGE": b"frame \xff\xfe \x1b[31mred"},
]


def run(*args: str, **options) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "console_tui", *args], capture_output=True, timeout=120, **options)


def test_a_robot_journal_reads_back_every_field(tmp_path):
    journal = make_journal(tmp_path / "robot.journal", [{**e, "_HOSTNAME": "robot1"} for e in ENTRIES])
    done = run("convert", str(journal), "--format", "jsonl", "-o", "-")
    assert done.returncode == 0, done.stderr
    records = [json.loads(line) for line in done.stdout.splitlines()]
    shown = [(r["level"], r["node"], r["msg"], r["file"], r["function"], r["line"]) for r in records]
    assert shown == [
        (20, "nav_bringup", "starting", "", "", 0),
        (30, "nav.planner", "no path from (0, 0)", "", "", 0),
        (50, "nav.planner", "giving up", "", "", 0),
        (40, "battery.py", "battery low: 9%", "/opt/robot/battery.py", "check", 88),
        (50, "kernel", "usb 1-1: device descriptor read/64, error -71", "", "", 0),
        (
            40,
            "arm_driver",
            'Traceback (most recent call last):\n  File "arm.py", line 3\nValueError: bad joint',
            "",
            "",
            0,
        ),
        (10, "camera", "frame \ufffd\ufffd \x1b[31mred", "", "", 0),
    ]
    assert [r["stamp_ns"] for r in records][1:3] == [1765000000001000007, 1765000000002000000], "the ROS stamps"
    assert {r.get("robot", "") for r in records} == {""}, "one file: no fleet (a directory's hosts are robots)"
    assert {r["source"] for r in records} == {"robot.journal"}
    assert "2 entries read back as ROS 2 records" in done.stderr.decode()
    # on the terminal nothing raw: the escape sequence shows as its stand-in
    lines = run("tail", str(journal), "--format", "{severity} {name}: {message}").stdout.decode().splitlines()
    assert lines[-1] == "DEBUG camera: frame \ufffd\ufffd ␛[31mred"
    assert lines[1] == "WARN nav.planner: no path from (0, 0)"


def test_a_fleet_directory_is_one_journal_of_several_robots(tmp_path):
    remote = tmp_path / "remote"
    remote.mkdir()
    make_journal(remote / "remote-picker.journal", [{"_HOSTNAME": "picker", "MESSAGE": f"p{i}"} for i in range(3)])
    make_journal(
        remote / "remote-cart.journal",
        [{"_HOSTNAME": "cart", "MESSAGE": f"c{i}"} for i in range(3)],
        first_us=1_765_000_000_000_500,
    )
    done = run("tail", str(remote), "--json")
    assert done.returncode == 0, done.stderr
    records = [json.loads(line) for line in done.stdout.splitlines()]
    assert [(r["robot"], r["msg"]) for r in records] == [
        ("picker", "p0"),
        ("cart", "c0"),
        ("picker", "p1"),
        ("cart", "c1"),
        ("picker", "p2"),
        ("cart", "c2"),
    ]
    # journal:PATH with --since: the same journal from a time on (journalctl's words for it)
    since = run("convert", f"journal:{remote}", "--since", "@1765000000.0012", "--format", "jsonl", "-o", "-")
    assert since.returncode == 0, since.stderr
    assert [json.loads(line)["msg"] for line in since.stdout.splitlines()] == ["c1", "p2", "c2"]


def test_the_rosout_copy_and_the_journal_copy_are_one_record(tmp_path):
    """A node logging to /rosout and through rcl_logging_syslog: console-tui rosout's log and the
    robot's journal hold each message; merged, each is one record naming both."""
    rosout = tmp_path / "rosout.log"
    rosout.write_text(
        ROS2_HEADER
        + "\n1765000000.001000007 WARN nav.planner [/src/planner.cpp:120(plan)] no path from (0, 0)\n"
        + "1765000000.002000000 FATAL nav.planner [/src/planner.cpp:130(plan)] giving up\n"
    )
    journal = make_journal(tmp_path / "robot.journal", [{**e, "_HOSTNAME": "robot1"} for e in ENTRIES[:3]])
    done = run("convert", str(rosout), str(journal), "--format", "jsonl", "-o", "-")
    assert done.returncode == 0, done.stderr
    records = [json.loads(line) for line in done.stdout.splitlines()]
    assert [(r["msg"], r["file"], r["source"]) for r in records] == [
        ("starting", "", "robot.journal"),
        ("no path from (0, 0)", "/src/planner.cpp", "rosout.log + robot.journal"),
        ("giving up", "/src/planner.cpp", "rosout.log + robot.journal"),
    ]


@pytest.mark.parametrize("how", ["-f", "journal:"])
def test_a_growing_journal_is_followed(tmp_path, how):
    journal = make_journal(tmp_path / "remote-robot1.journal", [{"MESSAGE": "before", "_HOSTNAME": "robot1"}])
    argument = [str(journal), "-f"] if how == "-f" else [f"journal:{journal}"]
    tail = TailProcess(dict(os.environ), *argument, "--format", "{message}")
    try:
        assert tail.take_text(1) == ["before"]
        make_journal(journal, [{"MESSAGE": "after", "_HOSTNAME": "robot1"}], first_us=1_765_000_001_000_000)
        assert tail.take_text(1) == ["after"]
    finally:
        assert tail.stop() == 0, b"".join(tail.stderr)[-2000:]


def test_without_a_journal_here_tail_and_convert_say_so():
    if not local_journal_problem():
        pytest.skip("this machine has a journal: the message for one without it cannot be seen here")
    tail = run("tail", "journal:")
    assert tail.returncode == 2 and b"this machine has no systemd journal" in tail.stderr
    convert = run("convert", "journal:nav.service", "-o", "-")
    assert convert.returncode == 2 and b"this machine has no systemd journal" in convert.stderr


def test_the_live_journal_of_this_machine():
    """Where journald runs: a line sent with logger(1) arrives through journal:."""
    problem = local_journal_problem()
    if problem:
        pytest.skip(f"no live journal to read: {problem} (containers usually have none)")
    tag = f"console-tui-test-{time.monotonic_ns()}"
    tail = TailProcess(dict(os.environ), "journal:", "--format", "{name} {message}")
    try:
        time.sleep(1.0)
        subprocess.run(["logger", "-t", tag, "hello journal"], check=True, timeout=30)
        lines = tail.take_text(2000, timeout=30)
    finally:
        tail.stop()
    assert f"{tag} hello journal" in lines


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
def test_the_app_shows_a_journal_file(tmp_path, monkeypatch, size):
    journal_remote()
    journal = make_journal(tmp_path / "robot.journal", ENTRIES)

    async def script(pilot) -> None:
        app = pilot.app
        await until(pilot, lambda: "7/7 shown" in screen_text(app), what=lambda: screen_text(app))
        text = screen_text(app)
        assert "nav.planner" in text and "no path from (0, 0)" in text and "battery low: 9%" in text
        assert "\x1b" not in text and "␛[31mred" in text
        await pilot.press("q")

    code, _apps = run_main(monkeypatch, ["--utc", str(journal)], script, size=size)
    assert code == 0
