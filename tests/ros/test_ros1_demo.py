"""``console-tui --demo --ros1``: a roscore of its own and rospy demo nodes, whose messages the
ROS 1 source reads, all of which end with the console (even when it is killed)."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import textwrap
import time

import pytest

from support.ros1_source import Collected
from support.rosproc import wait_until

pytestmark = pytest.mark.ros1


def _alive(pid: int) -> bool:
    """Running (a zombie left for a container's init to reap counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _group_pids(leader: int) -> list[int]:
    result = subprocess.run(["pgrep", "-g", str(leader)], capture_output=True, text=True)
    return [int(pid) for pid in result.stdout.split()]


def test_demo_nodes_log_through_their_own_roscore_and_stop_with_it(ros1_env):
    from console_tui.demo.ros1_launcher import Ros1Demo

    demo = Ros1Demo()
    assert ros1_env["ROS_MASTER_URI"] != demo.master_uri  # its own master, never the user's
    demo.start()
    try:
        with Collected() as got:
            expected = {"/count_and_log", "/navigation/planner", "/sensors/lidar_driver", "/power/battery_monitor"}
            got.wait(lambda c: expected <= {r.node for r in c.records}, timeout=60, what="every demo node")
            assert demo.status.problem == ""
            assert got.status.origin == f"ROS 1 {demo.master_uri}"
            planned = next(r for r in got.records if r.msg.startswith("Planned path"))
            assert planned.file == "behaviours.py" and planned.function == "plan_path" and planned.line > 0
        pids = [p.pid for p in demo.processes]
        core = demo.roscore.pid
        master_and_rosout = demo._master_processes()
        assert len(master_and_rosout) == 2 and len(_group_pids(core)) == 2  # the watchdog and roscore
    finally:
        demo.stop()
    assert not os.path.exists(demo._folder)
    assert wait_until(lambda: not any(_alive(pid) for pid in pids + master_and_rosout))
    assert wait_until(lambda: not _group_pids(core))


def test_demo_roscore_and_nodes_end_when_the_console_dies(ros1_env):
    script = textwrap.dedent(
        """
        import time
        from console_tui.demo.ros1_launcher import Ros1Demo
        from console_tui.ros.ros1.master import probe_master
        demo = Ros1Demo(["battery_monitor"])
        demo.start()
        while not demo.processes:
            time.sleep(0.1)
        others = demo._master_processes()
        print(demo._folder, flush=True)
        print(demo.roscore.pid, " ".join(str(p) for p in [*others, *(p.pid for p in demo.processes)]), flush=True)
        time.sleep(120)
        """
    )
    parent = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=ros1_env)
    try:
        folder = parent.stdout.readline().strip()
        core, *nodes = (int(pid) for pid in parent.stdout.readline().split())
        assert nodes and all(_alive(pid) for pid in nodes) and _group_pids(core)
        time.sleep(1.0)
    finally:
        parent.kill()
        parent.wait(5)
    assert len(nodes) == 3  # rosmaster, rosout, the node
    assert wait_until(lambda: not any(_alive(pid) for pid in nodes)), "demo processes outlived the console"
    assert wait_until(lambda: not _group_pids(core)), "roscore outlived the console"
    assert folder.startswith(tempfile.gettempdir())
    assert wait_until(lambda: not os.path.exists(folder)), "the demo's folder outlived the console"
