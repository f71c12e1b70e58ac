"""The logs a ROS run leaves (issue 19): ROS 1 Python logs (master.log, roslaunch, rospy
nodes), roscpp/rospy console output, ROS 2 launch.log and saved ``ros2 launch`` output.

The fixture files in ``tests/data/ros_log`` were written for these tests in the layouts
the tools write (checked against a real roslaunch run here and public captures)."""

from __future__ import annotations

import time

import pytest

from console_tui.model.formats import (
    FormatError,
    LaunchLogFormat,
    PythonLogFormat,
    Ros1ConsoleFormat,
    detect_text_format,
    text_formats,
)
from console_tui.model.formats.mixed_output import process_of_file, ros1_node_of_process
from console_tui.sources.files import open_log_file

from support.formats import DATA, read_cleanly, read_text

RUN = DATA / "ros_log" / "c0ffee00-d4b2-11eb-9c3e-0242ac110002"
LAUNCH = DATA / "ros_log" / "2024-10-05-00-46-21-512000-robot-4242"
T0 = 1624512194_000_000_000  # 2021-06-24 05:23:14 UTC


@pytest.fixture
def zone(monkeypatch):
    """Set the local time zone (the ROS 1 Python logs' times are local)."""

    def set_zone(name: str) -> None:
        monkeypatch.setenv("TZ", name)
        time.tzset()

    set_zone("UTC")
    yield set_zone
    monkeypatch.undo()
    time.tzset()


def _read(path, text_format, *, mtime_ns=0):
    return read_text(path.read_bytes(), text_format.for_file(path.name, mtime_ns), path.name)


def _rows(records):
    return [(r.stamp_ns, r.level, r.node, r.msg) for r in records]


def test_roslaunch_log_with_a_continued_message(zone):
    fmt = PythonLogFormat().for_file("roslaunch-robot-4242.log")
    records = read_cleanly((RUN / "roslaunch-robot-4242.log").read_bytes(), fmt, "roslaunch")
    args = "roslaunch starting with args ['/opt/ros/noetic/bin/roslaunch', 'demo', 'talker.launch']"
    assert _rows(records) == [
        (
            T0 + 584_000_000,
            20,
            "roslaunch",
            "Checking log directory for disk usage. This may take a while.\nPress Ctrl-C to interrupt",
        ),
        (T0 + 594_000_000, 20, "roslaunch", "Done checking log file disk usage. Usage is <1GB."),
        (T0 + 595_000_000, 20, "roslaunch", args),
        (T0 + 1_101_000_000, 20, "roslaunch.pmon", "start_process_monitor: creating ProcessMonitor"),
        (T0 + 2_900_000_000, 20, "roslaunch", "process[talker-2]: started with pid [4301]"),
        (T0 + 7_002_000_000, 30, "roslaunch", "process[talker-2]: required process died"),
    ]
    assert {r.source for r in records} == {"roslaunch"} and {r.file for r in records} == {""}
    assert fmt.notes() == ["its times are local times without a zone: read as this computer's local time (UTC+0000)"]


def test_master_log_times_are_read_as_local_time(zone):
    records, _ = _read(RUN / "master.log", PythonLogFormat())
    assert [(r.stamp_ns, r.node) for r in records] == [
        (T0 + 1_010_000_000, "rosmaster.main"),
        (T0 + 1_011_000_000, "rosmaster.main"),
        (T0 + 2_950_000_000, "rosmaster.master"),
    ]
    zone("Europe/Berlin")  # CEST in June: two hours ahead of UTC
    fmt = PythonLogFormat().for_file("master.log")
    later, _ = read_text((RUN / "master.log").read_bytes(), fmt, "master.log")
    assert [r.stamp_ns for r in later] == [r.stamp_ns - 2 * 3600 * 1_000_000_000 for r in records]
    assert fmt.notes()[0].endswith("(CET, UTC+0100)") or fmt.notes()[0].endswith("(CEST, UTC+0200)")


def test_rospy_node_log_names_the_node_and_keeps_the_traceback(zone):
    records, problems = _read(RUN / "talker-2.log.1", PythonLogFormat())
    assert list(problems) == []
    assert _rows(records) == [
        (T0 + 2_950_000_000, 20, "rospy.client", "init_node, name[/talker], pid[4301]"),
        (T0 + 2_990_000_000, 20, "rospy.topics", "topicmanager initialized"),
        (T0 + 3_562_000_000, 20, "/talker", "你好，世界: hello 1"),  # the logger 'rosout': the node's own message
        (T0 + 4_100_000_000, 40, "/talker", "failed\nTraceback (most recent call last):"),
    ]


def test_a_file_starting_inside_a_record_keeps_those_lines_as_a_row(zone):
    """talker-2.log begins with the end of a traceback (the rest is in talker-2.log.1):
    read alone, those lines are a row of the node, at the time of the record after them."""
    fmt = PythonLogFormat().for_file("talker-2.log")
    records = read_cleanly((RUN / "talker-2.log").read_bytes(), fmt, "talker-2.log")
    assert _rows(records) == [
        (T0 + 6_990_000_000, 20, "/talker", '  File "talker.py", line 18, in main'),
        (T0 + 6_990_000_000, 20, "/talker", "ZeroDivisionError: division by zero"),
        (T0 + 6_990_000_000, 20, "rospy.core", "signal_shutdown [atexit]"),
    ]
    assert fmt.notes()[1:] == [
        "2 plain lines (no log record) became rows of their own, at INFO",
        "2 records before the file's first time: that time",
    ]


def test_rospy_stdout_capture():
    fmt = Ros1ConsoleFormat().for_file("talker-2-stdout.log")
    records = read_cleanly((RUN / "talker-2-stdout.log").read_bytes(), fmt, "out")
    assert _rows(records) == [
        (1624512197_562810000, 20, "/talker", "talker starting"),
        (1624512197_562810000, 20, "/talker", "你好，世界: hello 1\na line printed after it"),
        (1624512199_562810000, 20, "/talker", "hello 2"),
    ]


def test_roscpp_console_capture_with_wall_and_sim_time_and_colour():
    data = (
        b"[ INFO] [1579418624.945503644, 0.500000000]: started\n"
        b"\x1b[33m[ WARN] [1579418625.000000001, 0.555000000]: slow \xe6\x97\xa5\xe6\x9c\xac\x1b[0m\n"
        b"[ERROR] [1579418625.5]: multi\n"
        b"line\n"
        b"[DEBUG] [1579418626.000000000]: \x1b]0;PWNED\x07 and \x1b[2J kept as they are\n"
    )
    fmt = Ros1ConsoleFormat().for_file("ns1-cam_driver-7-stdout.log")
    records = read_cleanly(data, fmt, "cap")
    assert _rows(records) == [
        (1579418624_945503644, 20, "/ns1/cam_driver", "started"),
        (1579418625_000000001, 30, "/ns1/cam_driver", "slow 日本"),
        (1579418625_500000000, 40, "/ns1/cam_driver", "multi\nline"),
        (1579418626_000000000, 10, "/ns1/cam_driver", "\x1b]0;PWNED\x07 and \x1b[2J kept as they are"),
    ]
    assert fmt.notes() == ["2 lines carry simulated time too: the stamps are wall-clock times"]


def test_launch_log():
    fmt = LaunchLogFormat().for_file("launch.log")
    records = read_cleanly((LAUNCH / "launch.log").read_bytes(), fmt, "launch.log")
    died = (
        "process has died [pid 4245, exit code 255, cmd "
        "'/opt/ros/humble/lib/sllidar_ros2/sllidar_node --ros-args -r __node:=sllidar_node']."
    )
    assert _rows(records) == [
        (
            1728089181_520000000,
            20,
            "launch",
            "All log files can be found below /home/robot/.ros/log/2024-10-05-00-46-21-512000-robot-4242",
        ),
        (1728089181_521000000, 20, "launch", "Default logging verbosity is set to INFO"),
        (1728089181_600000000, 20, "sllidar_node-1", "process started with pid [4245]"),
        (
            1728089182_885399753,
            20,
            "sllidar_node",
            "SLLidar running on ROS2 package SLLidar.ROS2 SDK Version:1.0.1",
        ),
        (
            1728089182_886000000,
            40,
            "sllidar_node",
            "Error, cannot bind to the specified serial port /dev/ttyUSB0.\nprinted by the driver",
        ),
        (1728089183_200000000, 40, "sllidar_node-1", died),
    ]
    assert fmt.notes() == []


SCREEN = (
    "[INFO] [launch]: All log files can be found below /home/u/.ros/log/2024-10-05-00-46-21-512000-robot-4242\n"
    "[INFO] [launch]: Default logging verbosity is set to INFO\n"
    "[INFO] [talker-1]: process started with pid [1509]\n"
    "[INFO] [listener-2]: process started with pid [1511]\n"
    "[listener-2] [INFO] [1671253878.884025200] [listener]: I heard: [你好 1]\n"
    "[talker-1] [INFO] [1671253879.374483100] [talker]: Publishing: 'Hello World: 1'\n"
    "[gz-3] \n"
    "[gz-3] QObject::moveToThread: Current thread (0x5f58) is not the object's thread\n"
    "[talker-1] [WARN] [1671253879.874501800] [talker]: two\n"
    "[talker-1] lines\n"
    "[listener-2] a line printed by the listener\n"
    "[ERROR] [talker-1]: process has died [pid 1509, exit code -6, cmd 'talker'].\n"
    "Traceback from nowhere\n"
)


def test_saved_ros2_launch_output():
    fmt = LaunchLogFormat().for_file("output.txt")
    records = read_cleanly(SCREEN.encode(), fmt, "output.txt")
    first, talker, warned = 1671253878_884025200, 1671253879_374483100, 1671253879_874501800
    assert _rows(records) == [
        (first, 20, "launch", SCREEN.split("\n")[0].split(": ", 1)[1]),
        (first, 20, "launch", "Default logging verbosity is set to INFO"),
        (first, 20, "talker-1", "process started with pid [1509]"),
        (first, 20, "listener-2", "process started with pid [1511]"),
        (first, 20, "listener", "I heard: [你好 1]"),
        (talker, 20, "talker", "Publishing: 'Hello World: 1'"),
        (talker, 20, "gz-3", ""),
        (talker, 20, "gz-3", "QObject::moveToThread: Current thread (0x5f58) is not the object's thread"),
        (warned, 30, "talker", "two\nlines"),
        (warned, 20, "listener-2", "a line printed by the listener"),
        (warned, 40, "talker-1", "process has died [pid 1509, exit code -6, cmd 'talker'].\nTraceback from nowhere"),
    ]
    assert fmt.notes() == [
        "3 plain lines (no log record) became rows of their own, at INFO",
        "4 records without a time of their own: the time of the record before",
        "4 records before the file's first time: that time",
    ]


def test_a_capture_without_any_time_takes_the_file_time():
    fmt = Ros1ConsoleFormat().for_file("rosout-1-stdout.log", 1624512195_000_000_000)
    records, _ = read_text((RUN / "rosout-1-stdout.log").read_bytes(), fmt, "x")
    assert [(r.stamp_ns, r.node) for r in records] == [(1624512195_000_000_000, "/rosout")] * 3
    assert fmt.notes()[-1] == "3 records with the file's modification time: the file gives no time"


@pytest.mark.parametrize(
    "path, expected",
    [
        (RUN / "roslaunch-robot-4242.log", "rospy-log"),
        (RUN / "master.log", "rospy-log"),
        (RUN / "talker-2.log.1", "rospy-log"),
        (RUN / "talker-2.log", "rospy-log"),  # starts with two lines of no record
        (RUN / "talker-2-stdout.log", "ros1-console"),
        (RUN / "rosout.log", "rosout"),
        (LAUNCH / "launch.log", "launch"),
        (DATA / "ros_log" / "sllidar_node_4245_1728089181700.log", "rcutils"),
    ],
    ids=lambda value: getattr(value, "name", value),
)
def test_each_run_log_is_recognised_by_its_content(path, expected):
    assert detect_text_format(path.read_bytes(), text_formats(), "renamed.txt").name == expected


def test_captured_output_without_any_log_line_is_known_by_its_name(tmp_path):
    prints = b"logging to /x/rosout.log\nsubscribed to /rosout\n"
    with pytest.raises(FormatError, match="not a log file this tool knows"):
        detect_text_format(prints, text_formats(), "notes.txt")
    (tmp_path / "rosout-1-stdout.log").write_bytes(prints)
    (tmp_path / "rosout-1-stdout.log.2").write_bytes(prints)
    assert open_log_file(tmp_path / "rosout-1-stdout.log").title == "ROS 1 console output"
    assert open_log_file(tmp_path / "rosout-1-stdout.log.2").title == "ROS 1 console output"
    (tmp_path / "talker-1.log").write_bytes(prints)  # a launched process's own log: plain output
    assert open_log_file(tmp_path / "talker-1.log").title == "ROS 1 console output"
    (tmp_path / "notes.log").write_bytes(prints)
    with pytest.raises(FormatError):
        open_log_file(tmp_path / "notes.log")


def test_names_from_file_names():
    assert [process_of_file(n) for n in ("talker-2-stdout.log", "master.log.3", "launch.log", "x.txt")] == [
        "talker-2",
        "master",
        "launch",
        "",
    ]
    assert [ros1_node_of_process(p) for p in ("talker-2", "ns1-chat2-3", "rosout-1", "master", "my-node")] == [
        "/talker",
        "/ns1/chat2",
        "/rosout",
        "",
        "",
    ]


def test_a_record_too_long_is_cut_and_the_rest_kept(monkeypatch):
    from console_tui.model.formats import line_groups

    monkeypatch.setattr(line_groups, "MAX_RECORD_LINES", 3)
    data = b"[INFO] [1.000000000]: start\n" + b"".join(b"line %d\n" % i for i in range(5))
    records, problems = read_text(data, Ros1ConsoleFormat().for_file("a-1-stdout.log"), "x")
    assert [r.msg for r in records] == ["start\nline 0\nline 1", "line 2", "line 3", "line 4"]
    assert [p.line for p in problems] == [1] and "lines after the cut are rows of their own" in problems.items[0].what
