"""``console-tui run -- roslaunch FILE`` with Debian's roslaunch and two rospy nodes of the
tests' own (tests/nodes/launch_pkg): one prints to stdout (``output="log"``: its file), one
warns on the screen and dies of an exception. Every line shows once with its process (a log
message that came by /rosout and by the terminal or the file is one row), the death is an
ERROR with the traceback before it, and ``q`` stops the launch, leaving no process behind."""

from __future__ import annotations

import os
import re
import shutil
import sys
from pathlib import Path

import pytest

from console_tui.sources.launch.launched_command import group_members

from support.rosproc import NODES
from support.run_main import run_main
from support.ui import screen_text, until

PACKAGE = NODES / "launch_pkg"


def rows(app) -> list[str]:
    """The table's rows on the screen: ``SEV NODE MESSAGE`` (time and number cut off)."""
    shown = []
    for line in screen_text(app).splitlines():
        found = re.match(r"\s+\d+ \d\d:\d\d:\d\d\.\d{3} (?P<rest>(?:DEBUG|INFO|WARN|ERROR|FATAL).*)", line)
        if found:
            shown.append(" ".join(found["rest"].split()))
    return shown


def processes_of(marker: str) -> list[str]:
    """The command lines of running processes that name ``marker`` (this test's log folder)."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as cmdline:
                text = cmdline.read().replace(b"\0", b" ").decode(errors="replace")
            with open(f"/proc/{entry}/stat", encoding="ascii", errors="replace") as stat:
                zombie = stat.read().rsplit(")", 1)[1].split()[0] == "Z"
        except OSError:
            continue
        if marker in text and not zombie:
            found.append(f"{entry}: {text}")
    return found


def run_until_shown(monkeypatch, command: list[str], *words: str) -> tuple[list[str], str]:
    """``console-tui run -- COMMAND`` in this process at 220x70 until its rows hold each of
    ``words`` (and a moment more: what would come twice has come by then), then ``q``; the
    rows and the status line as they were shown."""
    seen: dict[str, object] = {}

    async def script(pilot) -> None:
        app = pilot.app

        def complete() -> bool:
            shown = rows(app)
            return all(any(word in row for row in shown) for word in words)

        await until(pilot, complete, timeout=90, what=lambda: screen_text(app))
        await pilot.pause(1.5)
        seen["rows"] = rows(app)
        seen["status"] = screen_text(app).splitlines()[app.main.status_bar.region.y]
        await pilot.press("q")

    code, _apps = run_main(monkeypatch, ["run", "--utc", "--", *command], script, size=(220, 70))
    assert code == 0
    return seen["rows"], seen["status"]  # type: ignore[return-value]


@pytest.mark.ros1
def test_run_roslaunch_shows_each_line_once_with_its_process(ros1_env, monkeypatch, tmp_path):
    if shutil.which("roslaunch") is None:
        pytest.skip("roslaunch is not installed (apt-get install ros-core)")
    monkeypatch.setenv("ROS_PACKAGE_PATH", f"{PACKAGE}{os.pathsep}/usr/share")
    command = ["roslaunch", str(PACKAGE / "two_nodes.launch")]
    shown, status = run_until_shown(monkeypatch, command, "process has died", "printer done")
    pid = int(re.search(r"running \(pid (\d+)\)", status)[1])  # type: ignore[index]
    text = "\n".join(shown)
    for number in range(3):
        assert shown.count(f"INFO /printer printed line {number}") == 1, text
        # on /rosout and in printer-N-stdout.log: one row, the /rosout copy (with its file and line)
        assert sum(f"logged message {number}" in row for row in shown) == 1, text
        assert any(row.startswith(f"INFO /printer logged message {number} printer.py") for row in shown), text
    assert sum("about to die" in row for row in shown) == 1, text
    assert any(row.startswith("WARN /dier about to die") for row in shown), text
    died = [row for row in shown if "process has died" in row]
    assert len(died) == 1 and died[0].startswith("ERROR /dier [dier-"), text
    tracebacks = [row for row in shown if "Traceback (most recent call last)" in row]
    assert len(tracebacks) == 1 and tracebacks[0].startswith("ERROR /dier Traceback"), text
    assert "↵ File " in tracebacks[0], "the traceback is one record of its lines"
    others = [row for row in shown if row not in tracebacks]
    assert not any("ValueError" in row or "in <module>" in row for row in others), "no line of it a row of its own"
    assert any(row.startswith("INFO /printer process[printer-") for row in shown), text
    assert any(row.startswith("INFO roslaunch SUMMARY") for row in shown), text
    # q stopped the launch as Ctrl+C at its terminal does: nothing of it is left
    assert group_members(pid) == []
    assert processes_of(str(tmp_path)) == []
    assert not any(Path(ros1_env["ROS_LOG_DIR"]).glob("*/dier-*-stdout.log")), "dier printed to the screen"


@pytest.mark.ros2
def test_run_a_ros2_launch_merges_each_process_console_with_rosout(ros_env, monkeypatch):
    """ROS 2 nodes under a stand-in for ``ros2 launch`` (tests/nodes/mini_launch.py: launch's
    screen format, as ros2 launch cannot be installed here): a node's console line (its
    stderr, after ``[counter-1]``) and its /rosout copy are one row, at the /rosout copy's
    stamp; what it prints is a row of its process; a death is an ERROR."""
    python = sys.executable
    command = [
        python,
        str(NODES / "mini_launch.py"),
        f"counter={python} {NODES / 'ros2_counter.py'} counter",
        f"crasher={python} {NODES / 'ros2_counter.py'} crasher --count 1 --exit 3",
    ]
    shown, status = run_until_shown(monkeypatch, command, "finished cleanly", "process has died")
    text = "\n".join(shown)
    for number in range(3):
        # once: the /rosout copy (with its file) stands for the console line too
        assert [row for row in shown if row.startswith(f"INFO counter count {number}")] == [
            next(row for row in shown if row.startswith(f"INFO counter count {number} ros2_counter.py"))
        ], text
        # its print, right after: a record of its own (the console line's copy cut where /rosout's ends)
        assert shown.count(f"INFO counter-1 printed {number}") == 1, text
    assert any(row.startswith("INFO crasher count 0 ros2_counter.py") for row in shown), text
    died = [row for row in shown if "process has died" in row]
    assert len(died) == 1 and died[0].startswith("ERROR crasher-2 process has died [pid"), text
    assert "exit code 3" in died[0]
    assert any(row.startswith("INFO counter-1 process has finished cleanly") for row in shown), text
    assert any(row.startswith("INFO launch Default logging verbosity") for row in shown), text
    assert "ROS 2 domain" in status
