"""A fleet's records in files, without ROS: saved with their robot (CSV: a last column only
when records name one; JSON Lines: a ``robot`` field), loaded back with it, and files given
after ``--robot NAME`` named for that robot."""

from __future__ import annotations

import pytest

from console_tui.cli import build_parser
from console_tui.commands.arguments import robot_files
from console_tui.model.formats.jsonl import JsonLinesFormat
from console_tui.model.formats.rqt_csv import RqtCsvFormat
from console_tui.model.formats.save import save_records
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.record import LogRecord
from console_tui.sources.files import FileLoad

from support.formats import read_cleanly


def fleet_records() -> list[LogRecord]:
    return [
        LogRecord(1_000_000_000 + i, 20, "/talker", f'say "{i}"', "t.py", "f", 3, robot=robot)
        for i, robot in enumerate(["picker", "cart", "", 'odd";"name'])
    ]


@pytest.mark.parametrize(
    ("save_format", "text_format"), [("rqt", RqtCsvFormat()), ("rqt1", RqtCsvFormat()), ("jsonl", JsonLinesFormat())]
)
def test_saves_keep_the_robot_and_loading_restores_it(tmp_path, save_format, text_format):
    path = tmp_path / "fleet.out"
    assert save_records(fleet_records(), path, save_format) == 4
    loaded = read_cleanly(path.read_bytes(), text_format)
    assert [(r.robot, r.msg) for r in loaded] == [(r.robot, r.msg) for r in fleet_records()]


def test_csv_has_the_robot_column_last_and_only_when_robots_exist(tmp_path):
    save_records(fleet_records(), tmp_path / "fleet.csv")
    head, first = (tmp_path / "fleet.csv").read_text().splitlines()[:2]
    assert head == "message;severity;node;stamp;location;robot"
    assert first.endswith(';"t.py:f:3";"picker"')
    plain = [LogRecord(1, 20, "/n", "m")]
    save_records(plain, tmp_path / "plain.csv")
    assert (tmp_path / "plain.csv").read_text().splitlines()[0] == "message;severity;node;stamp;location"
    save_records(iter(fleet_records()), tmp_path / "streamed.csv")  # an iterator: no column
    assert "robot" not in (tmp_path / "streamed.csv").read_text().splitlines()[0]


def test_jsonl_has_a_robot_field_only_for_records_with_one(tmp_path):
    save_records(fleet_records(), tmp_path / "fleet.jsonl")
    lines = (tmp_path / "fleet.jsonl").read_text().splitlines()
    assert '"robot": "picker"' in lines[0] and '"robot"' not in lines[2]


def test_robot_before_files_names_them():
    parser = build_parser()
    argv, robots = robot_files(
        parser, ["--robot", "picker", "a.csv", "dir", "--topic", "/x", "--robot=cart", "b.jsonl", "--utc", "--", "-c"]
    )
    assert argv == ["--topic", "/x", "--utc", "--", "a.csv", "dir", "b.jsonl", "-c"]
    assert robots == {"a.csv": "picker", "dir": "picker", "b.jsonl": "cart", "-c": "cart"}
    assert parser.parse_args(argv).files == ["a.csv", "dir", "b.jsonl", "-c"]
    assert robot_files(parser, ["x.csv", "--topic", "/rosout"]) == (["x.csv", "--topic", "/rosout"], {})


@pytest.mark.parametrize("argv", [["--robot"], ["--robot", "bad name", "a.csv"]])
def test_a_bad_robot_option_exits_2(argv, capsys):
    with pytest.raises(SystemExit) as exited:
        robot_files(build_parser(), argv)
    assert exited.value.code == 2
    assert "--robot" in capsys.readouterr().err


def test_files_and_folders_after_robot_get_its_name_unless_they_name_their_own(tmp_path):
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "rosout.log").write_text("1.000000000 INFO /n [f.py:1(f)] from the folder\n")
    (tmp_path / "other.log").write_text("2.000000000 INFO /n [f.py:1(f)] from the other\n")
    save_records(fleet_records()[:2], tmp_path / "saved.jsonl")
    queue = IntakeQueue()
    paths = [str(tmp_path / "run"), str(tmp_path / "other.log"), str(tmp_path / "saved.jsonl")]
    load = FileLoad(paths, queue, robots={paths[0]: "arm", paths[2]: "ignored"})
    load.start()
    assert load.join(30)
    got = {record.msg: record.robot for record in queue.drain()}
    assert got == {"from the folder": "arm", "from the other": "", 'say "0"': "picker", 'say "1"': "cart"}


def test_tail_prints_a_fleets_robot(tmp_path):
    from console_tui.model.formats.print_format import ROBOT_PREFIX, PrintFormat
    from console_tui.model.formats.rcutils_log import DEFAULT_TEMPLATE

    record = LogRecord(1_000_000_000, 30, "talker", "hi", robot="picker\x1b[31m")
    assert PrintFormat(ROBOT_PREFIX + DEFAULT_TEMPLATE).text(record).startswith("[picker␛[31m] [WARN] [")
    assert PrintFormat("{robot}|${node}").text(record) == "picker␛[31m|talker"
    from console_tui.commands.tail import build_parser as tail_parser

    args = tail_parser().parse_args(["--domain", "3=a", "--master", "127.0.0.1:11311=b"])
    assert [robot.name for robot in args.robots] == ["a", "b"]


def test_robots_from_names_names_each_file_for_itself(tmp_path, monkeypatch):
    from console_tui import run_app
    from console_tui.cli import main
    from console_tui.ros.fleet import robot_name_for

    assert robot_name_for("logs/picker/") == "picker"
    assert robot_name_for("/x/cart.rosout.log") == "cart"
    assert robot_name_for("fork lift#2.jsonl") == "fork_lift_2"
    assert robot_name_for("...") == "robot"
    seen = {}
    monkeypatch.setattr(run_app, "run_app", lambda args, end_process: seen.update(args.file_robots) or 0)
    assert main(["--robots-from-names", "a/picker", "--robot", "arm", "b.log", "c.log"]) == 0
    assert seen == {"a/picker": "picker", "b.log": "arm", "c.log": "arm"}
