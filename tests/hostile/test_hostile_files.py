"""Hostile files (issue 17): escape-laden names, markup and deep nesting in content,
FIFOs, endless lines and cut-off recordings. Nothing may hang, crash, or reach the
terminal raw; ``convert`` says what went wrong and exits non-zero."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import tracemalloc
from pathlib import Path

import pytest

from console_tui.model.formats import FormatError, JsonLinesFormat
from console_tui.sources.files import open_log_file

from support.formats import hostile_records, read_text

ESC = b"\x1b"
TITLE = "\x1b]0;PWNED\x07"
CLIPBOARD = "\x1b]52;c;cm0gLXJmIH4=\x07"


def convert(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[bytes]:
    """``console-tui convert`` in a process of its own, its output as bytes."""
    return subprocess.run(
        [sys.executable, "-m", "console_tui", "convert", *args], capture_output=True, timeout=timeout, check=False
    )


def test_escapes_in_file_names_never_reach_stderr(tmp_path):
    hostile = tmp_path / f"run{TITLE}{CLIPBOARD}.log"
    hostile.write_text("[INFO] [1.000000000] [n]: fine\n[INFO] [2.0")  # a problem that names the file
    missing = tmp_path / f"gone{TITLE}.bag"
    result = convert(str(hostile), str(missing), "-o", str(tmp_path / f"out{CLIPBOARD}.csv"))
    assert result.returncode == 1
    assert ESC not in result.stderr and b"\x07" not in result.stderr
    err = result.stderr.decode()
    assert "␛]0;PWNED␇" in err  # shown, as visible stand-ins
    assert "gone␛]0;PWNED␇.bag: no such file or directory" in err


def test_escapes_in_messages_and_problems_never_reach_stderr(tmp_path):
    data = "\n".join(["[INFO] [1.000000000] [n]: ok", f"{TITLE} stray text before nothing"])
    bad = tmp_path / "bad.jsonl"
    bad.write_text(json.dumps({"stamp_ns": 1, "msg": "m"}) + f"\n{{not json {TITLE}\n")
    log = tmp_path / "a.log"
    log.write_text(data + "\n")
    result = convert(str(bad), str(log), "-o", str(tmp_path / "out.csv"))
    assert result.returncode == 1 and ESC not in result.stderr


def test_markup_in_jsonl_values_loads_as_plain_text():
    lines = [
        json.dumps({"stamp_ns": 1, "msg": "[/]", "node": "[bold]n[/bold]"}),
        '{"stamp_ns": 2, "msg": "[/] unclosed',
        "[/]",
    ]
    records, problems = read_text("\n".join(lines).encode() + b"\n", JsonLinesFormat(), "[/]x.jsonl")
    assert [(r.msg, r.node) for r in records] == [("[/]", "[bold]n[/bold]")]
    assert [p.line for p in problems] == [2, 3]
    assert all(type(p.what) is str and type(str(p)) is str for p in problems)


def test_jsonl_nested_a_million_deep_is_a_problem_not_a_traceback(tmp_path):
    deep = tmp_path / "deep.jsonl"
    good = json.dumps({"stamp_ns": 1, "msg": "fine"})
    deep.write_text(good + "\n" + '{"stamp_ns": 2, "msg": ' + "[" * 1_000_000 + "]" * 1_000_000 + "}\n")
    result = convert(str(deep), "-o", "-")
    assert b"Traceback" not in result.stderr and b"RecursionError" not in result.stderr
    assert result.returncode == 1
    assert b"line 2: JSON nested too deeply" in result.stderr
    assert result.stdout.count(b"\n") == 2  # header and the good record
    only = tmp_path / "only.jsonl"
    only.write_text("[" * 1_000_000 + "]" * 1_000_000 + "\n")
    result = convert(str(only), "-o", "-")
    assert result.returncode == 2 and result.stdout == b"" and b"Traceback" not in result.stderr


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_a_fifo_is_refused_at_once(tmp_path):
    fifo = tmp_path / "pipe.log"
    os.mkfifo(fifo)
    with pytest.raises(FormatError, match=r"pipe\.log: a named pipe \(FIFO\), not a file"):
        open_log_file(fifo)
    result = convert(str(fifo), "-o", "-", timeout=30)  # hung for ever before
    assert result.returncode == 2 and b"named pipe" in result.stderr


def test_an_endless_line_costs_a_bounded_amount(tmp_path, monkeypatch):
    from console_tui.model.formats import line_groups

    monkeypatch.setattr(line_groups, "MAX_LINE", 4 << 20)
    monkeypatch.setattr(line_groups, "MAX_RECORD_CHARS", 4 << 20)
    path = tmp_path / "one-line.log"
    with open(path, "wb") as out:
        out.write(b"[INFO] [1.000000000] [n]: ")
        for _ in range(40):
            out.write(b"x" * (1 << 20))
        out.write(b"\n[INFO] [2.000000000] [n]: after\n")
    log_file = open_log_file(path)
    tracemalloc.start()
    try:
        records = [r for batch in log_file.batches() for r in batch]
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert [len(r.msg) for r in records] == [(4 << 20) - len(b"[INFO] [1.000000000] [n]: "), 5]
    assert peak < 40 << 20, f"peak {peak / 1e6:.0f} MB for a 40 MB line cut at 4 MB"
    (problem,) = log_file.problems
    assert problem.line == 1 and "the 37,748,762 bytes after them left out" in problem.what


def test_a_truncated_mcap_with_no_record_says_so_and_fails(tmp_path):
    pytest.importorskip("mcap")
    from support.recordings import write_rosbag2

    bag = write_rosbag2(tmp_path / "cut", hostile_records(), storage="mcap")
    whole = next(bag.glob("*.mcap"))
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(whole.read_bytes()[:300])
    result = convert(str(cut), "-o", str(tmp_path / "out.csv"))
    assert result.returncode == 2
    assert b"cut.mcap" in result.stderr and b"nothing written" in result.stderr
    assert not (tmp_path / "out.csv").exists()


def test_opening_a_fifo_never_blocks_the_caller(tmp_path):
    """A FIFO is refused before anything opens it (opening one for reading blocks)."""
    fifo = tmp_path / "rosout.log"
    os.mkfifo(fifo)
    done = threading.Event()

    def attempt() -> None:
        try:
            open_log_file(fifo)
        except FormatError:
            pass
        done.set()

    threading.Thread(target=attempt, daemon=True).start()
    assert done.wait(10)


def test_a_socket_a_device_and_a_path_through_a_file_are_refused_with_what_they_are(tmp_path):
    import socket

    sock_path = tmp_path / "talk.sock"
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    server.bind(str(sock_path))
    try:
        with pytest.raises(FormatError, match=r"talk\.sock: a socket, not a file"):
            open_log_file(sock_path)
    finally:
        server.close()
    with pytest.raises(FormatError, match=r"null: a device, not a file"):
        open_log_file("/dev/null")
    plain = tmp_path / "plain.log"
    plain.write_text("1.000000000 INFO /a [a.py:1(f)] [topics: /rosout] one\n")
    with pytest.raises(FormatError, match=r"inside: cannot read: Not a directory"):
        open_log_file(plain / "inside")


def test_rotated_parts_none_of_which_can_be_read_name_the_first_failure(tmp_path):
    from console_tui.sources.files.folders import LogPaths
    from console_tui.sources.files.opener import open_log_paths

    binary = tmp_path / "node.log.1"
    binary.write_bytes(b"\x00\x01\x02 not text at all \xff\xfe" * 50)
    missing = tmp_path / "node.log"  # listed, then gone before it was read
    with pytest.raises(FormatError, match=r"^node\.log: node\.log\.1: "):
        open_log_paths(LogPaths((binary, missing), "node.log"))
    with pytest.raises(FormatError, match=r"^node\.log: node\.log: cannot read: No such file"):
        open_log_paths(LogPaths((missing, binary), "node.log"))


_AS_ANOTHER_USER = """
import contextlib, io, os, sys
from console_tui.cli import main
with contextlib.redirect_stderr(io.StringIO()):  # everything it imports, loaded while we may
    main(["convert", sys.argv[1] + "/a", "-o", sys.argv[2] + ".warm", "--format", "jsonl"])
if os.geteuid() == 0:  # root enters every folder: become nobody, for whom the folder is closed
    os.setgid(65534)
    os.setuid(65534)
sys.exit(main(["convert", sys.argv[1], "-o", sys.argv[2], "--format", "jsonl"]))
"""


def test_a_subfolder_that_cannot_be_entered_is_skipped_and_reported(tmp_path):
    """Issue 33 item 8: ``convert runs/`` with one closed subfolder loads the rest and names it."""
    import tempfile

    base = Path(tempfile.mkdtemp(prefix="console-tui-closed-"))  # outside pytest's private tmp
    try:
        base.chmod(0o777)
        runs = base / "runs"
        for name in ("a", "b", "closed"):
            (runs / name).mkdir(parents=True)
            (runs / name / "rosout.log").write_text(
                f"1700000000.000000000 INFO /n{name} [f.py:1(g)] [topics: /rosout] hello from {name}\n"
            )
        for path in (runs, runs / "a", runs / "b"):
            path.chmod(0o755)
        (runs / "a" / "rosout.log").chmod(0o644)
        (runs / "b" / "rosout.log").chmod(0o644)
        (runs / "closed").chmod(0o600)  # listable by its owner only, enterable by none but root
        out = base / "out.jsonl"
        # Not measured by coverage (whose process configuration the environment carries): its data
        # file is beside the checkout, where the user nobody may not write.
        env = {key: value for key, value in os.environ.items() if not key.startswith("COVERAGE_")}
        done = subprocess.run(
            [sys.executable, "-c", _AS_ANOTHER_USER, str(runs), str(out)],
            capture_output=True,
            text=True,
            timeout=120,
            env=env,
        )
        assert "Traceback" not in done.stderr, done.stderr
        assert "closed" in done.stderr and "Permission denied" in done.stderr
        text = out.read_text()
        assert "hello from a" in text and "hello from b" in text
    finally:
        (base / "runs" / "closed").chmod(0o700)
        import shutil

        shutil.rmtree(base, ignore_errors=True)
