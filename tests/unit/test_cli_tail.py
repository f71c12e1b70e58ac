"""``console-tui tail`` on files: formats of both ROS syntaxes, JSON, rules, inert text,
colour, closed pipes, and following a growing (and rotated) file. No ROS needed."""

from __future__ import annotations

import json
import os
import pty
import re
import select
import subprocess
import sys
import time
from pathlib import Path

import pytest

from console_tui.commands.tail import use_color
from console_tui.model.formats.print_format import PrintFormat
from console_tui.model.formats.rosout_log import ROS2_HEADER, rosout_log_text
from console_tui.model.formats.rotating_file import RotatingFile
from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import RuleSet
from console_tui.model.rules.stream import StreamFilter
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView

from support.feed import records as feed_records
from support.formats import hostile_records
from support.tail_process import TailProcess

ENV = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[2])}
ENV.pop("NO_COLOR", None)


def write_log(path: Path, records: list[LogRecord]) -> Path:
    path.write_text(ROS2_HEADER + "".join(rosout_log_text(r) for r in records))
    return path


def tail(*args: str, env: dict | None = None, timeout: float = 30) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "console_tui", "tail", *args],
        capture_output=True,
        env=env or ENV,
        timeout=timeout,
    )


RECORDS = [
    LogRecord(1_700_000_000_000_000_000, 20, "talker", "hello", "/src/t.py", "tick", 42),
    LogRecord(1_700_000_001_500_000_000, 40, "nav.planner", "failed\nno path", "p.cpp", "plan", 7),
]


def test_default_format_is_ros2_console_output(tmp_path):
    result = tail(str(write_log(tmp_path / "rosout.log", RECORDS)))
    assert result.returncode == 0 and result.stderr == b""
    assert result.stdout.decode() == (
        "[INFO] [1700000000.000000000] [talker]: hello\n[ERROR] [1700000001.500000000] [nav.planner]: failed\nno path\n"
    )


def test_rosconsole_and_rcutils_tokens(tmp_path):
    path = str(write_log(tmp_path / "rosout.log", RECORDS))
    ros1 = tail(
        path,
        "--utc",
        "--format",
        "${severity} ${time:%H:%M:%S} ${node} ${logger}: ${message} @${file}:${line} ${function}",
    )
    assert ros1.stdout.decode().splitlines()[0] == "INFO 22:13:20 talker talker: hello @/src/t.py:42 tick"
    ros2 = tail(
        path,
        "--utc",
        "--format",
        "{severity}|{time_as_nanoseconds}|{date_time_with_ms}|{file_name}:{line_number}:{function_name}|{name}|{message}",
    )
    assert ros2.stdout.decode().splitlines()[:2] == [
        "INFO|1700000000000000000|2023-11-14 22:13:20.000|/src/t.py:42:tick|talker|hello",
        "ERROR|1700000001500000000|2023-11-14 22:13:21.500|p.cpp:7:plan|nav.planner|failed",
    ]
    mixed = tail(path, "--format", "[${severity}] {name}\\t{message}")
    assert mixed.stdout.decode().splitlines()[0] == "[INFO] talker\thello"
    bad = tail(path, "--format", "${thread} ${message}")
    assert bad.returncode == 2 and b"${thread}" in bad.stderr and b"not in a log message" in bad.stderr


def test_environment_format_is_the_default(tmp_path):
    path = str(write_log(tmp_path / "rosout.log", RECORDS))
    result = tail(path, env={**ENV, "RCUTILS_CONSOLE_OUTPUT_FORMAT": "{severity}: {message}"})
    assert result.stdout.decode().splitlines()[0] == "INFO: hello"
    # As ROS prints it: rcutils leaves an unknown {...} in the environment's format as text.
    lenient = tail(path, env={**ENV, "RCUTILS_CONSOLE_OUTPUT_FORMAT": "{message} {unknown}"})
    assert lenient.returncode == 0 and lenient.stdout.decode().splitlines()[0] == "hello {unknown}"


@pytest.mark.parametrize("template", ["{nmae}: {message}", "${nope} ${message}"])
def test_an_unknown_token_in_format_is_refused_with_the_list(tmp_path, template):
    path = str(write_log(tmp_path / "rosout.log", RECORDS))
    result = tail(path, "--format", template)
    assert result.returncode == 2 and result.stdout == b""
    err = result.stderr.decode()
    assert "--format: unknown token" in err and "Traceback" not in err
    assert "{message}" in err or "${message}" in err  # the tokens there are
    if "nmae" in template:
        assert "did you mean {name}?" in err


def test_json_lines_are_the_apps_jsonl(tmp_path):
    result = tail(str(write_log(tmp_path / "rosout.log", RECORDS)), "--json")
    lines = [json.loads(line) for line in result.stdout.decode().splitlines()]
    assert lines[1] == {
        "stamp_ns": 1_700_000_001_500_000_000,
        "level": 40,
        "node": "nav.planner",
        "msg": "failed\nno path",
        "file": "p.cpp",
        "function": "plan",
        "line": 7,
        "source": "rosout.log",
    }


#: Bytes a terminal acts on, or characters that hide: C0 but newline and tab, DEL, C1, bidi,
#: zero-width space, BOM, tags.
TERMINAL_ACTIVE = re.compile(
    rb"[\x00-\x08\x0b-\x1f\x7f]|\xc2[\x80-\x9f]|\xe2\x80[\x8b\xaa-\xae]|\xe2\x81[\xa6-\xa9]|\xef\xbb\xbf|\xf3\xa0"
)


def test_hostile_messages_are_printed_inert(tmp_path):
    records = hostile_records()
    records.append(
        LogRecord(
            1_800_000_000_000_000_000,
            20,
            "evil\x1b]0;title\x07",
            "\x9b31m\u202eevil\x7f\u200b\ufeff\U000e0041",
            "\x1b[2J",
            "f",
            1,
        )
    )
    path = str(write_log(tmp_path / "rosout.log", records))
    for args in ((), ("--json",), ("--format", "${node} ${file} ${function}: ${message}")):
        out = tail(path, *args).stdout
        assert TERMINAL_ACTIVE.search(out) is None, (args, TERMINAL_ACTIVE.search(out))
    text = tail(path).stdout.decode()
    assert "[evil␛]0;title␇]: <U+009B>31m<U+202E>evil␡<U+200B><U+FEFF><U+E0041>" in text
    assert "␛[31mcolour␛[0m" in text
    back = [json.loads(line) for line in tail(path, "--json").stdout.decode().splitlines()]
    assert [r["msg"] for r in back] == [r.msg for r in records]  # inert and lossless


def test_query_and_rules_file(tmp_path):
    path = str(write_log(tmp_path / "rosout.log", RECORDS))
    assert tail(path, "--query", "level>=warn").stdout.decode().startswith("[ERROR]")
    rules = tmp_path / "rules.toml"
    rules.write_text('[[rules]]\nrole = "exclude"\nkind = "node"\nnames = ["nav*"]\n')
    assert tail(path, "--rules", str(rules)).stdout.decode().splitlines() == [
        "[INFO] [1700000000.000000000] [talker]: hello"
    ]
    bad = tail(path, "--query", "level>=loud")
    assert bad.returncode == 2 and b"--query is not valid" in bad.stderr


def test_files_merged_by_time_and_a_bad_file_reported(tmp_path):
    first = write_log(tmp_path / "a.log", [RECORDS[1]])
    second = write_log(tmp_path / "b.log", [RECORDS[0]])
    result = tail(str(first), str(second), str(tmp_path / "missing.log"), "--format", "{message}")
    assert result.stdout.decode() == "hello\nfailed\nno path\n"
    assert result.returncode == 1 and b"missing.log: no such file" in result.stderr


def test_a_closed_pipe_ends_it_quietly(tmp_path):
    many = [LogRecord(1_700_000_000_000_000_000 + n, 20, "n", f"message {n}") for n in range(100_000)]
    path = write_log(tmp_path / "big.log", many)
    command = f"set -o pipefail; {sys.executable} -m console_tui tail {path} | head -1"
    result = subprocess.run(["bash", "-c", command], capture_output=True, env=ENV, timeout=60)
    assert result.returncode == 0 and result.stderr == b""
    assert result.stdout == b"[INFO] [1700000000.000000000] [n]: message 0\n"


def run_on_terminal(args: list[str], env: dict) -> bytes:
    controller, terminal = pty.openpty()
    process = subprocess.Popen(
        [sys.executable, "-m", "console_tui", "tail", *args], stdout=terminal, stderr=subprocess.DEVNULL, env=env
    )
    os.close(terminal)
    output = b""
    while True:
        ready, _, _ = select.select([controller], [], [], 20)
        if not ready:
            break
        try:
            data = os.read(controller, 65536)
        except OSError:
            break
        if not data:
            break
        output += data
    process.wait(10)
    os.close(controller)
    return output


def test_colour_on_a_terminal_only_and_never_with_no_color(tmp_path):
    path = str(write_log(tmp_path / "rosout.log", RECORDS))
    coloured = run_on_terminal([path], {**ENV, "TERM": "xterm"})
    assert b"\x1b[31m[ERROR]" in coloured
    assert b"\x1b[" not in run_on_terminal([path], {**ENV, "TERM": "xterm", "NO_COLOR": "1"})
    assert b"\x1b[" not in tail(path).stdout  # a pipe
    assert b"\x1b[31m" in tail(path, "--color", "always").stdout
    # A flag wins over the environment (no-color.org): --color always colours despite NO_COLOR.
    assert b"\x1b[31m[ERROR]" in tail(path, "--color", "always", env={**ENV, "NO_COLOR": "1"}).stdout
    assert b"\x1b[" not in run_on_terminal([path, "--color", "never"], {**ENV, "TERM": "xterm"})
    assert b"\x1b[" not in run_on_terminal([path, "--no-color"], {**ENV, "TERM": "xterm"})


def test_use_color():
    class Tty:
        def isatty(self) -> bool:
            return True

    assert use_color("auto", Tty(), {"TERM": "xterm"})
    assert not use_color("auto", Tty(), {"TERM": "dumb"})
    assert not use_color("auto", Tty(), {"NO_COLOR": "1"})
    assert use_color("auto", Tty(), {"NO_COLOR": ""})
    assert not use_color("auto", object(), {})
    assert use_color("always", object(), {"NO_COLOR": "x"})
    assert not use_color("never", Tty(), {"TERM": "xterm"})


def test_follow_a_growing_and_rotated_file(tmp_path):
    path = tmp_path / "rosout.log"
    log = RotatingFile(path, max_bytes=2048, keep=2, header=ROS2_HEADER)

    def put(first: int, count: int) -> None:
        log.write(
            [
                rosout_log_text(LogRecord(10**18 + n, 20, "n", f"line {n}" + ("\nmore" if n % 7 == 0 else "")))
                for n in range(first, first + count)
            ]
        )
        log.flush()

    put(0, 3)
    follower = TailProcess(ENV, "-f", str(path), "--format", "{message}")
    try:
        assert follower.take_text(4) == ["line 0", "more", "line 1", "line 2"]
        put(3, 2)
        assert follower.take_text(2) == ["line 3", "line 4"]
        for first in range(5, 205, 20):  # rotated every few steps, as a busy node's log is
            put(first, 20)
            time.sleep(0.3)
        expected = []
        for n in range(5, 205):
            expected += [f"line {n}", "more"] if n % 7 == 0 else [f"line {n}"]
        assert follower.take_text(len(expected)) == expected
        assert log.rotations >= 3
        assert follower.stop(10) == 0
        assert follower.stderr == []
    finally:
        follower.stop()
        log.close()


def test_stream_filter_agrees_with_the_view():
    records = feed_records(2000)
    for query in ("level>=warn", "-node:nav* +timeout", "+level:error", "node:sensors.*"):
        rules = RuleSet().with_query(parse_query(query))
        store = LogStore()
        store.extend_records(
            [
                LogRecord(
                    **{
                        f: getattr(r, f)
                        for f in ("stamp_ns", "level", "node", "msg", "file", "function", "line", "source")
                    }
                )
                for r in records
            ]
        )
        view = LogView(store, rules)
        while not view.refilter_step(1.0):
            pass
        expected = [(store.get(view.seq_at(row)).msg, view.decoration_of(view.seq_at(row))) for row in range(len(view))]
        got = []
        stream_filter = StreamFilter(rules)
        for start in range(0, len(records), 300):
            got += [(r.msg, d) for r, d in stream_filter.filter(records[start : start + 300])]
        assert got == expected, query


@pytest.mark.parametrize("template", [None, "${message}", "{message}"])
def test_print_format_keeps_newlines_and_tabs(template):
    line = PrintFormat(template).text(LogRecord(0, 20, "n", "a\tb\r\nc"))
    assert line.endswith("a\tb\nc")


def test_a_folder_with_rotated_files_and_last(tmp_path):
    run = tmp_path / "log" / "rosout-2026-11-22-10-00-00-42"
    run.mkdir(parents=True)
    older = [LogRecord(10**18 + n, 20, "n", f"old {n}") for n in range(3)]
    newer = [LogRecord(10**18 + n, 20, "n", f"new {n}") for n in range(3, 5)]
    write_log(run / "rosout.log.1", older)
    write_log(run / "rosout.log", newer)
    expected = ["old 0", "old 1", "old 2", "new 3", "new 4"]
    assert tail(str(run), "--format", "{message}").stdout.decode().splitlines() == expected
    env = {**ENV, "ROS_LOG_DIR": str(tmp_path / "log")}
    assert tail("--last", "--format", "{message}", env=env).stdout.decode().splitlines() == expected
    # Followed: the rotated file is read first, then the newest one is followed.
    follower = TailProcess(ENV, "-f", str(run), "--format", "{message}")
    try:
        assert follower.take_text(5) == expected
        with open(run / "rosout.log", "a") as log:
            log.write(rosout_log_text(LogRecord(10**18 + 5, 20, "n", "new 5")))
        assert follower.take_text(1) == ["new 5"]
        assert follower.stop(10) == 0
    finally:
        follower.stop()
    missing = tail("--last", env={**ENV, "ROS_LOG_DIR": str(tmp_path / "none")})
    assert missing.returncode == 2 and b"--last: no ROS log directory" in missing.stderr
