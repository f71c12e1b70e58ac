"""A fleet without ROS: the command line's and fleet files' robots, checked; records that
carry their robot through batches, the pipe and the store; one intake process per robot."""

from __future__ import annotations

import pytest

from console_tui.cli import build_parser
from console_tui.commands.arguments import check_fleet_arguments
from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import BatchPacker, BatchUnpacker, RecordColumns
from console_tui.ros.fleet import FleetError, Robot, load_fleet, parse_domain, parse_master
from console_tui.ros.ros_version import ROS1, ROS2
from console_tui.sources.intake_process.parent import ProcessSource

from support.rosproc import wait_until


def test_domain_and_master_options_with_and_without_names():
    assert parse_domain("3") == Robot("domain3", ROS2, domain=3)
    assert parse_domain("3=picker") == Robot("picker", ROS2, domain=3)
    assert parse_master("http://10.0.0.7:11311=forklift") == Robot("forklift", ROS1, master="http://10.0.0.7:11311/")
    assert parse_master("127.0.0.1:11400").master == "http://127.0.0.1:11400/"
    assert parse_master("127.0.0.1:11400").name == "127.0.0.1_11400"


@pytest.mark.parametrize(
    ("parse", "text", "says"),
    [
        (parse_domain, "233", "from 0 to 232"),
        (parse_domain, "three", "from 0 to 232"),
        (parse_domain, "3=bad name", "a robot's name"),
        (parse_domain, "3=", "a robot's name"),
        (parse_master, "http://host", "a URI such as"),
        (parse_master, "ftp://host:1", "a URI such as"),
        (parse_master, "http://host:99999", "a URI such as"),
    ],
)
def test_bad_options_say_what_is_wrong(parse, text, says):
    with pytest.raises(FleetError, match=says):
        parse(text)


def test_the_command_line_keeps_robots_in_order_and_mixes_files(tmp_path):
    fleet = tmp_path / "fleet.toml"
    fleet.write_text(
        '[[robot]]\nname = "arm"\ndomain = 7\ncolour = "cyan"\n\n'
        '[[robot]]\nname = "cart"\nmaster = "http://127.0.0.1:11400"\ntopic = "/rosout"\n'
    )
    args = build_parser().parse_args(["--domain", "3=picker", "--fleet", str(fleet), "--master", "127.0.0.1:11500=old"])
    assert [(r.name, r.origin) for r in args.robots] == [
        ("picker", "ROS 2 domain 3"),
        ("arm", "ROS 2 domain 7"),
        ("cart", "ROS 1 http://127.0.0.1:11400/"),
        ("old", "ROS 1 http://127.0.0.1:11500/"),
    ]
    assert args.robots[1].colour == "cyan" and args.robots[2].topic == "/rosout"
    assert build_parser().parse_args([]).robots is None


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (["--domain", "3=a", "--domain", "4=a"], "two robots are named 'a'"),
        (["--domain", "3", "--domain", "3=b"], "'domain3' and 'b' are both ROS 2 domain 3"),
    ],
)
def test_two_robots_with_one_name_or_source_are_refused(argv, says, capsys):
    parser = build_parser()
    args = parser.parse_args(argv)
    with pytest.raises(SystemExit) as exited:
        check_fleet_arguments(parser, args)
    assert exited.value.code == 2
    assert says in capsys.readouterr().err


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("", "no robots"),
        ("robots = 1", "unknown table 'robots'"),
        ("[[robot]]\ndomain = 1", "robot 1: needs a name"),
        ('[[robot]]\nname = "a"', "robot 1 (a): give either a domain (ROS 2) or a master (ROS 1)"),
        ('[[robot]]\nname = "a"\ndomain = 1\nmaster = "h:1"', "give either a domain"),
        ('[[robot]]\nname = "a"\ndomain = -1', "robot 1 (a): domain: a ROS 2 domain"),
        ('[[robot]]\nname = "a"\ndomain = 1\ncolour = "puce"', "colour: one of"),
        ('[[robot]]\nname = "a"\ndomain = 1\ntopic = "rosout"', "topic: a topic name"),
        ('[[robot]]\nname = "a"\ndomain = 1\nspeed = 3', "unknown field 'speed'"),
        ('[[robot]]\nname = "a"\ndomain = 1\n[[robot]]\nname = "a"\ndomain = 2', "two robots are named 'a'"),
        ("[[robot]\n", "not a TOML file"),
    ],
)
def test_bad_fleet_files_are_refused_saying_where(tmp_path, text, says):
    path = tmp_path / "fleet.toml"
    path.write_text(text)
    with pytest.raises(FleetError) as error:
        load_fleet(path)
    assert str(error.value).startswith(str(path))
    assert says in str(error.value)


def test_a_missing_or_binary_fleet_file_is_refused(tmp_path):
    with pytest.raises(FleetError, match="cannot be read"):
        load_fleet(tmp_path / "none.toml")
    (tmp_path / "bin.toml").write_bytes(b"\xff\xfe\x00")
    with pytest.raises(FleetError, match="not a TOML file"):
        load_fleet(tmp_path / "bin.toml")


def test_a_robots_environment_points_its_intake_at_it():
    base = {"ROS_DOMAIN_ID": "1", "ROS_MASTER_URI": "http://elsewhere:1/", "OTHER": "x"}
    assert Robot("a", ROS2, domain=5).environment(base) == {**base, "ROS_DOMAIN_ID": "5", "ROS_VERSION": "2"}
    ros1 = Robot("b", ROS1, master="http://127.0.0.1:2/").environment(base)
    assert ros1["ROS_MASTER_URI"] == "http://127.0.0.1:2/" and ros1["ROS_VERSION"] == "1" and ros1["OTHER"] == "x"


def record(i: int, robot: str = "") -> LogRecord:
    return LogRecord(1_000 + i, 20, f"node{i % 2}", f"m{i}", robot=robot)


def test_robots_cross_batches_and_the_pipe_and_cost_nothing_without():
    records = [record(i, "ab"[i % 2]) for i in range(6)]
    columns = RecordColumns.from_records(records)
    assert columns.robots == list("ababab")
    assert RecordColumns.from_records([record(1)]).robots is None
    packer, unpacker = BatchPacker(), BatchUnpacker()
    assert [r.robot for r in unpacker.unpack(packer.pack(columns)).records()] == list("ababab")
    assert unpacker.unpack(packer.pack(RecordColumns.from_records([record(1)]))).robots is None
    joined = RecordColumns.joined([columns, RecordColumns.from_records([record(9)])])
    assert joined.robots == [*"ababab", ""]
    assert columns.kept([True, False] * 3).robots == ["a"] * 3
    assert columns.slice(1, 3).robots == ["b", "a"]
    named = RecordColumns.from_records([record(i) for i in range(3)]).of_robot("c")
    assert [r.robot for r in named.records()] == ["c"] * 3


def test_the_store_keeps_each_records_robot_in_a_column_made_only_when_needed():
    store = LogStore()
    store.extend_records([record(i) for i in range(3)])
    assert store.get(0).robot == "" and store.robot_id_of(0) == 0
    chunk = next(store.spans(0, 3)).chunk
    assert chunk.robots is None
    store.extend(RecordColumns.from_records([record(i) for i in range(3)]).of_robot("picker"))
    assert chunk.robots is not None and list(chunk.robots) == [0, 0, 0, 1, 1, 1]
    store.extend_records([record(9)])
    assert [r.robot for r in store] == ["", "", "", "picker", "picker", "picker", ""]
    assert store.robots[store.robot_id_of(4)] == "picker"
    store.extend(RecordColumns.from_records([record(i) for i in range(CHUNK_SIZE)]).of_robot("cart"))
    assert store.get(store.end_seq - 1).robot == "cart"


def test_each_intake_process_names_its_robot_on_records_and_status():
    queue = IntakeQueue()
    sources = [
        ProcessSource(queue, "synthetic", args=["--rate", "5000", "--count", "200"], robot=name)
        for name in ("picker", "cart")
    ]
    for source in sources:
        source.start()
    records: list = []
    try:
        assert wait_until(lambda: records.extend(queue.drain()) or len(records) >= 400, 30)
        assert wait_until(lambda: all(s.status.robot and s.status.running for s in sources), 30)
    finally:
        for source in sources:
            source.stop()
    assert sorted({r.robot for r in records}) == ["cart", "picker"]
    assert sum(r.robot == "picker" for r in records) == 200
    assert [s.status.robot for s in sources] == ["picker", "cart"]


def test_rosout_runs_on_the_domain_given(capsys):
    from console_tui.commands.rosout import build_parser as rosout_parser

    assert rosout_parser().parse_args(["--domain", "7"]).domain == 7
    assert rosout_parser().parse_args([]).domain is None
    with pytest.raises(SystemExit):
        rosout_parser().parse_args(["--domain", "233"])
    assert "0 to 232" in capsys.readouterr().err


def test_the_demo_is_no_fleet(capsys):
    from console_tui.cli import main

    with pytest.raises(SystemExit) as exited:
        main(["--demo", "--domain", "3"])
    assert exited.value.code == 2
    assert "--demo starts its own nodes" in capsys.readouterr().err


def test_a_fleets_batches_of_one_moment_merge_by_stamp():
    picker = RecordColumns.from_records([record(i * 10, "picker") for i in range(4)])  # 1000, 1010 ...
    cart = RecordColumns.from_records([record(i * 10 + 5, "cart") for i in range(3)])
    merged = RecordColumns.in_time_order([picker, cart])
    assert list(merged.stamps) == [1000, 1005, 1010, 1015, 1020, 1025, 1030]
    assert merged.robots == ["picker", "cart"] * 3 + ["picker"]
    assert [r.msg for r in merged.records()] == ["m0", "m5", "m10", "m15", "m20", "m25", "m30"]
    same = RecordColumns.in_time_order([RecordColumns.from_records([record(1, "a"), record(1, "b")])])
    assert same.robots == ["a", "b"]  # one stamp: the order given
