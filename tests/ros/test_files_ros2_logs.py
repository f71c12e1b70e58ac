"""ROS 2 log files written by real rclpy nodes (rcl's spdlog sink) in a temporary
ROS_LOG_DIR, read back: the default format and a custom RCUTILS_CONSOLE_OUTPUT_FORMAT."""

from __future__ import annotations

import time

import pytest

from console_tui.sources.files import open_log_file

from support.rosproc import NodeProcesses

pytestmark = pytest.mark.ros2

CUSTOM = "{time_as_nanoseconds} {severity} {name} [{file_name}:{line_number} {function_name}] {message}"
# A message line that repeats a whole record header ("[INFO] [1.0...] [x]: ") would read
# as a new record: the file format cannot tell them apart. One that starts like it can.
HOSTILE = 'multi\nline "quoted"; semi;\n\nnaïve ✓ 日本語\n[INFO] [not a record'


def _run_talker(env: dict[str, str], log_dir, name: str, extra_env: dict[str, str]) -> tuple[int, list[dict]]:
    processes = NodeProcesses({**env, "ROS_LOG_DIR": str(log_dir), **extra_env})
    try:
        talker = processes.start("talker.py", "--name", name, "--namespace", "/files", "--debug")
        ready = talker.expect("ready")
        talker.send({"cmd": "log_all", "tag": name})
        logged = talker.expect("logged")["messages"]
        talker.lines.clear()
        talker.send({"cmd": "log", "level": "warn", "msg": HOSTILE})
        logged += talker.expect("logged")["messages"]
    finally:
        processes.stop_all()  # spdlog flushes the file when the node exits
    return ready["pid"], logged


@pytest.mark.parametrize("template", [None, CUSTOM])
def test_log_files_of_real_nodes(ros_env, tmp_path, template):
    started = time.time_ns()
    extra = {"RCUTILS_CONSOLE_OUTPUT_FORMAT": template} if template else {}
    pid, logged = _run_talker(ros_env, tmp_path, "filer", extra)
    [path] = tmp_path.glob(f"*_{pid}_*.log")
    log_file = open_log_file(path, log_format=template)
    records = [r for batch in log_file.batches() for r in batch]
    assert list(log_file.problems) == []
    assert [(r.level, r.msg) for r in records] == [(m["level"], m["msg"]) for m in logged]
    assert {r.node for r in records} == {"files.filer"}
    assert all(started <= r.stamp_ns <= time.time_ns() for r in records)
    assert {r.source for r in records} == {path.name}
    if template:
        assert [(r.file, r.function, r.line) for r in records] == [
            (m["file"], m["function"], m["line"]) for m in logged
        ]
