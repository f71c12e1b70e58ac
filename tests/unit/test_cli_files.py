"""The command line for files: FILE..., --log-format, --live, and 'convert' end to end."""

from __future__ import annotations

import json

from console_tui.cli import build_parser, main

from support.formats import DATA


def test_file_arguments():
    args = build_parser().parse_args(["a.bag", "b.log", "--live", "--log-format", "{severity} {message}"])
    assert args.files == ["a.bag", "b.log"] and args.live and args.log_format == "{severity} {message}"
    args = build_parser().parse_args([])
    assert args.files == [] and not args.live and args.log_format is None


def test_convert_rqt_to_jsonl_and_back_gives_the_same_bytes(tmp_path, capsys):
    original = DATA / "rqt_console_ros2.csv"
    jsonl = tmp_path / "saved.jsonl"
    assert main(["convert", str(original), "-o", str(jsonl)]) == 0
    lines = [json.loads(line) for line in jsonl.read_text().splitlines()]
    assert len(lines) == 11 and {line["source"] for line in lines} == {"rqt_console_ros2.csv"}
    back = tmp_path / "back.csv"
    assert main(["convert", str(jsonl), "-o", str(back)]) == 0
    # convert merges by time: the file's one record stamped 0 comes first
    rows = original.read_text().split("\n")
    assert back.read_text().split("\n") == [rows[0], rows[-2], *rows[1:-2], ""]
    assert "11 records from 1 file written" in capsys.readouterr().err


def test_convert_reports_problems_and_unreadable_inputs(tmp_path, capsys):
    bad = tmp_path / "bad.log"
    bad.write_text("[INFO] [1.000000000] [n]: fine\n[INFO] [2.0000")
    out = tmp_path / "out.csv"
    assert main(["convert", str(bad), str(tmp_path / "missing.bag"), "-o", str(out)]) == 1
    err = capsys.readouterr().err
    assert "missing.bag: no such file or directory" in err
    assert "bad.log: line 2: the file ends in the middle of a line" in err
    assert out.read_text().startswith("message;severity;node;stamp;location\n")


def test_convert_to_stdout_and_unwritable_output(tmp_path, capsys):
    assert main(["convert", str(DATA / "rqt_console_ros1.csv"), "--format", "jsonl", "-o", "-"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 5
    assert main(["convert", str(DATA / "rqt_console_ros1.csv"), "-o", str(tmp_path / "no" / "x.csv")]) == 2
    assert "cannot write" in capsys.readouterr().err


def test_convert_exit_status_says_how_it_went(tmp_path, capsys):
    """0 clean, 1 written with problems, 2 nothing written (issue 11, item 5)."""
    good = DATA / "rqt_console_ros2.csv"
    out = tmp_path / "out.csv"
    assert main(["convert", str(good), "-o", str(out)]) == 0
    damaged = tmp_path / "damaged.csv"
    damaged.write_bytes(good.read_bytes() + b"GARBAGE\n")
    assert main(["convert", str(damaged), "-o", str(out)]) == 1
    assert "damaged.csv: line 17: not a rqt_console CSV record: 'GARBAGE'" in capsys.readouterr().err
    assert main(["convert", str(tmp_path / "missing.csv"), "-o", "-"]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""  # no CSV header before the failure
    assert "missing.csv: no such file or directory" in captured.err and "nothing written" in captured.err
    assert main(["convert", str(tmp_path / "missing.csv"), "-o", str(tmp_path / "new.csv")]) == 2
    assert not (tmp_path / "new.csv").exists()


def test_convert_reads_a_kinetic_rosout_log(tmp_path, capsys):
    log = tmp_path / "rosout.log"
    log.write_bytes(b"0.000000000 INFO [/path/main.cpp:167(MapServer) [topics: /rosout] msg [/x\n" * 451)
    out = tmp_path / "out.jsonl"
    assert main(["convert", str(log), "-o", str(out)]) == 0
    lines = out.read_text().splitlines()
    assert len(lines) == 451 and json.loads(lines[0])["function"] == "MapServer"
    assert "451 records from 1 file written" in capsys.readouterr().err
