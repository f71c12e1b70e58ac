"""``console-tui tail`` on the live stream, with real ROS 2 nodes: both format syntaxes,
JSON, hostile text printed inert, and ``| head -1`` exiting 0."""

from __future__ import annotations

import json
import subprocess
import sys
import time

import pytest

from support.rosproc import group_alive, wait_until
from support.tail_process import TailProcess

pytestmark = pytest.mark.ros2

HOSTILE = "evil \x1b[2J\x1b]0;title\x07 \u202edesrever\x9b1m end"


def subscribed(node, count: int) -> bool:
    """At least ``count`` tails (hidden console-tui nodes) subscribe to /rosout."""
    infos = node.get_subscriptions_info_by_topic("/rosout")
    return sum(info.node_name.startswith("_console_tui_log_") for info in infos) >= count


def test_live_formats_json_and_inert_text(nodes, ros_env, ros_runtime):
    talker = nodes.start("talker.py", "--name", "tailed", "--namespace", "/t", "--debug")
    talker.expect("ready")
    variants = {
        "default": (),
        "ros1": ("--topic", "/rosout", "--format", "${severity}|${node}|${message}|${file}:${line}|${function}"),
        "rcutils": (
            "--topic",
            "/rosout",
            "--format",
            "{severity}|{name}|{message}|{file_name}:{line_number}|{function_name}",
        ),
        "json": ("--topic", "/rosout", "--json"),
        "errors": ("--topic", "/rosout", "--query", "level>=error node:t.*", "--format", "{severity} {message}"),
    }
    tails = {name: TailProcess(ros_env, *args) for name, args in variants.items()}
    try:
        # Subscribed: what is logged now reaches every one of them (as history if need be).
        probe = ros_runtime.create_node("probe")
        assert wait_until(lambda: subscribed(probe, len(tails)), 60)
        time.sleep(1.0)
        talker.send({"cmd": "log_all", "tag": "live"})
        logged = talker.expect("logged")["messages"]
        talker.send({"cmd": "log", "level": "warn", "msg": HOSTILE})
        talker.expect_next("logged")
        out = {name: tail.take(6 if name != "errors" else 2) for name, tail in tails.items()}
        for name, tail in tails.items():
            assert tail.stop() == 0, (name, b"".join(tail.stderr)[-2000:])
    finally:
        for tail in tails.values():
            tail.stop()

    names = ["DEBUG", "INFO", "WARN", "ERROR", "FATAL"]
    default = [line.decode() for line in out["default"]]
    for line, message, name in zip(default, logged, names, strict=False):
        assert line.startswith(f"[{name}] [") and line.endswith(f"] [t.tailed]: {message['msg']}\n")
    assert default[5] == default[5].replace("\x1b", "")  # nothing raw
    assert "␛[2J␛]0;title␇ <U+202E>desrever<U+009B>1m end" in default[5]
    for name, separator_line in (("ros1", out["ros1"]), ("rcutils", out["rcutils"])):
        first = separator_line[0].decode().rstrip("\n").split("|")
        assert first == [
            "DEBUG",
            "t.tailed",
            logged[0]["msg"],
            f"{logged[0]['file']}:{logged[0]['line']}",
            logged[0]["function"],
        ], name
    records = [json.loads(line) for line in out["json"]]
    assert [(r["level"], r["node"], r["msg"], r["file"], r["function"], r["line"]) for r in records[:5]] == [
        (m["level"], "t.tailed", m["msg"], m["file"], m["function"], m["line"]) for m in logged
    ]
    assert records[5]["msg"] == HOSTILE and b"\x1b" not in out["json"][5] and "\u202e".encode() not in out["json"][5]
    assert [line.decode() for line in out["errors"]] == ["ERROR live error message\n", "FATAL live fatal message\n"]


def test_head_closing_the_pipe_ends_it_with_status_0(nodes, ros_env):
    talker = nodes.start("talker.py", "--name", "piped")
    talker.expect("ready")
    talker.send({"cmd": "periodic", "period": 0.05})
    talker.expect("periodic")
    command = f"set -o pipefail; {sys.executable} -m console_tui tail --topic /rosout | head -1"
    result = subprocess.run(["bash", "-c", command], capture_output=True, env=ros_env, timeout=60)
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.startswith(b"[INFO] [") and result.stdout.count(b"\n") == 1
    assert result.stderr == b""


def test_head_ends_it_at_once_on_a_quiet_graph(nodes, ros_env, ros_runtime):
    """One message, then nothing: ``tail | head -1`` ends without waiting for a second."""
    talker = nodes.start("talker.py", "--name", "lonely")
    talker.expect("ready")
    command = f"set -o pipefail; {sys.executable} -m console_tui tail --topic /rosout | head -1"
    pipeline = subprocess.Popen(["bash", "-c", command], env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        probe = ros_runtime.create_node("tail_probe")
        assert wait_until(lambda: subscribed(probe, 1), timeout=60), "the tail never subscribed"
        talker.send({"cmd": "log", "level": "info", "msg": "the only message"})
        out, err = pipeline.communicate(timeout=60)  # no second message ever comes
    finally:
        if pipeline.poll() is None:
            pipeline.kill()
            pipeline.wait()
    assert pipeline.returncode == 0, err[-2000:]
    assert out.endswith(b"[lonely]: the only message\n") and err == b""


@pytest.mark.ros1
def test_ros1_live_through_the_same_source_choice(roscore, ros1_nodes, ros1_env):
    ros1_nodes.rospy("rospy_node.py", "py_tailed", "--period", "0.1").expect("ready")
    tail = TailProcess(
        ros1_env, "--ros1", "--query", "node:*py_tailed level>=warn", "--format", "${severity} ${node} ${message}"
    )
    try:
        lines = [line.decode() for line in tail.take(2)]
    finally:
        assert tail.stop() == 0, b"".join(tail.stderr)[-2000:]
    assert len(lines) == 2 and all(line.split()[1] == "/py_tailed" for line in lines)
    assert {line.split()[0] for line in lines} <= {"WARN", "ERROR", "FATAL"}


@pytest.mark.ros1
def test_ros1_level_is_filtered_by_the_intake_and_said_once(roscore, ros1_nodes, ros1_env):
    """ROS 1 has no content filter: ``--level error`` drops the rest in the intake process."""
    ros1_nodes.rospy("rospy_node.py", "py_leveled", "--period", "0.1", "--debug").expect("ready")
    tail = TailProcess(ros1_env, "--ros1", "--level", "error", "--format", "${severity} ${node}")
    try:
        lines = tail.take_text(6)
    finally:
        assert tail.stop() == 0, b"".join(tail.stderr)[-2000:]
    assert len(lines) == 6 and set(lines) == {"ERROR /py_leveled", "FATAL /py_leveled"}, lines
    said = [line for line in b"".join(tail.stderr).decode().splitlines() if "--level" in line]
    assert said == [
        "console-tui tail: --level: level >= ERROR: filtered by the intake, not by the middleware "
        "(ROS 1 has no content filter)"
    ]


def test_the_slower_intake_path_is_said_once_on_stderr(nodes, ros_env):
    """Without the take loop in C (here switched off, as on a machine without cc or
    python3-dev) tail says so once, with what it costs, and prints as ever."""
    talker = nodes.start("talker.py", "--name", "slow_path")
    talker.expect("ready")
    tail = TailProcess({**ros_env, "CONSOLE_TUI_COMPILED_TAKE": "0"}, "--topic", "/rosout", "--format", "{message}")
    try:
        lines: list[str] = []

        def printed() -> bool:
            talker.send({"cmd": "log", "level": "info", "msg": "tick"})
            talker.expect_next("logged")
            lines.extend(tail.take_text(1, timeout=1))
            return "tick" in lines

        assert wait_until(printed, 60)
        assert tail.stop() == 0
    finally:
        tail.stop()
    said = [line for line in b"".join(tail.stderr).decode().splitlines() if "slower intake" in line]
    assert len(said) == 1, said
    assert said[0].startswith(
        "console-tui tail: slower intake: the take loop in C is not used (CONSOLE_TUI_COMPILED_TAKE=0)"
    )
    assert "python3-dev" in said[0]


def test_a_hanging_compiler_does_not_blind_the_intake(nodes, ros_env, ros_runtime, tmp_path):
    """Issue 33 item 10: with ``CC`` hanging and no built take loop cached, ``tail`` takes
    through rclpy meanwhile: what is logged arrives long before the compiler's time limit."""
    compiler = tmp_path / "hanging-cc"
    group_file = tmp_path / "compiler-group"
    compiler.write_text(f"#!/bin/sh\necho $$ > {group_file}\nsleep 100 &\nwait\n")
    compiler.chmod(0o755)
    env = {**ros_env, "CC": str(compiler), "XDG_CACHE_HOME": str(tmp_path / "cache")}
    talker = nodes.start("talker.py", "--name", "while_building")
    talker.expect("ready")
    tail = TailProcess(env, "--topic", "/rosout", "--format", "{message}")
    try:
        probe = ros_runtime.create_node("probe_building")
        assert wait_until(lambda: subscribed(probe, 1), 40)
        talker.send({"cmd": "log", "level": "warn", "msg": "logged while the compiler hangs"})
        lines = tail.take_text(1, timeout=40)  # the build's limit is 60 s, the compiler 100 s
        assert lines == ["logged while the compiler hangs"]
        assert wait_until(group_file.exists, 40), "the compiler never ran"
    finally:
        tail.stop()
    group = int(group_file.read_text())
    assert wait_until(lambda: not group_alive(group), 20), "the compiler outlived the console"


@pytest.mark.parametrize("content_filter", ["1", "0"])
def test_level_prints_that_severity_and_worse_and_says_when_the_middleware_does_not_filter(
    nodes, ros_env, ros_runtime, content_filter
):
    """``tail --level error`` (ros2 log watch's option): asked of DDS as a content filter, or
    with it switched off filtered in the intake process, said once on stderr; the same lines."""
    talker = nodes.start("talker.py", "--name", "leveled", "--debug")
    talker.expect("ready")
    env = {**ros_env, "CONSOLE_TUI_CONTENT_FILTER": content_filter}
    tail = TailProcess(env, "--topic", "/rosout", "--level", "error", "--format", "{severity} {message}")
    try:
        probe = ros_runtime.create_node("level_probe")
        assert wait_until(lambda: subscribed(probe, 1), 60)
        for number in range(2):
            talker.send({"cmd": "log_all", "tag": f"r{number}"})
            talker.expect_next("logged")
        lines = [line.decode() for line in tail.take(4)]
        assert tail.stop() == 0
    finally:
        tail.stop()
    assert lines == [f"{level} r{n} {level.lower()} message\n" for n in range(2) for level in ("ERROR", "FATAL")]
    said = [line for line in b"".join(tail.stderr).decode().splitlines() if "--level" in line]
    from rclpy.subscription import Subscription

    if content_filter == "1" and not hasattr(Subscription, "set_content_filter"):  # Jazzy's rclpy
        assert said == [
            "console-tui tail: --level: level >= ERROR: filtered by the intake, not by the middleware "
            "(this rclpy has no content filters (Jazzy's has none))"
        ]
    elif content_filter == "1":
        assert said == []
    else:
        assert said == [
            "console-tui tail: --level: level >= ERROR: filtered by the intake, not by the middleware "
            "(the content filter is switched off: CONSOLE_TUI_CONTENT_FILTER=0)"
        ]
