"""The one dispatch of positional arguments (``sources/locations.py``) and the options of each
kind (``commands/location_options.py``), as the app's, ``tail``'s and ``convert``'s command
lines read them."""

from __future__ import annotations

import time

import pytest

from console_tui import cli
from console_tui.commands import convert, tail
from console_tui.commands.location_options import apply_location_arguments
from console_tui.sources.locations import FILE, JOURNAL, KINDS, WAREHOUSE, location_kind, split_locations

NS = 1_000_000_000


def test_each_kind_by_its_text_and_files_as_ever(tmp_path):
    journal_file = tmp_path / "system.journal"
    journal_file.write_bytes(b"LPKSHHRH")
    assert [kind for kind, _ in KINDS] == [WAREHOUSE, JOURNAL]
    assert location_kind("run.log") == FILE
    assert location_kind(str(tmp_path)) == FILE
    assert location_kind(str(journal_file)) == FILE  # a journal file is read as a file
    assert location_kind("CHDB:///x") == WAREHOUSE
    assert location_kind("clickhouses://h/db") == WAREHOUSE
    assert location_kind("clickhouse://h:8123/db?table=logs") == WAREHOUSE
    assert location_kind("http://collector:4318") == FILE  # only sent to, never read
    assert location_kind("journal:") == JOURNAL
    assert location_kind("journal:nav.service") == JOURNAL
    assert location_kind("journal:/var/log/journal/remote") == JOURNAL
    assert split_locations(["a.log", "chdb:///x", "journal:nav", "b/", "journal:"]) == {
        FILE: ["a.log", "b/"],
        WAREHOUSE: ["chdb:///x"],
        JOURNAL: ["journal:nav", "journal:"],
    }


@pytest.mark.parametrize("parser_of", [cli.build_parser, tail.build_parser])
def test_one_since_for_the_journal_and_the_warehouse(parser_of):
    parser = parser_of()
    args = parser.parse_args(["--since", "2h", "journal:nav", "chdb:///tmp/w", "a.log"])
    before = time.time_ns()
    apply_location_arguments(parser, args, follow=True)
    assert args.files == ["a.log"]
    assert [address.text for address in args.warehouses] == ["chdb:///tmp/w"]
    assert [journal.units for journal in args.journals] == [("nav",)]
    assert args.journals[0].since == "-2h"  # as journalctl writes an age
    assert abs(before - 2 * 3600 * NS - args.since_ns) < 60 * NS
    assert args.until_ns is None
    # journalctl's own forms go to the journal as written
    args = parser.parse_args(["--since=-1h", "--unit", "arm.service"])
    apply_location_arguments(parser, args, follow=True)
    assert args.journals[0].since == "-1h" and args.journals[0].units == ("arm.service",)
    args = parser.parse_args(["--since", "yesterday", "journal:"])
    apply_location_arguments(parser, args, follow=True)
    assert args.journals[0].since == "yesterday" and args.since_ns is None


@pytest.mark.parametrize(
    ("argv", "said"),
    [
        (["--since", "1h", "a.log"], "--since goes with the journal or a log warehouse"),
        (["--until", "1h", "journal:"], "--until goes with a log warehouse"),
        (["--since", "yesterday", "chdb:///tmp/w"], "--since: not a time: 'yesterday'"),
        (["--since", "1h", "--until", "2h", "chdb:///tmp/w"], "--since is after --until"),
        (["clickhouse://"], "clickhouse://"),
    ],
)
def test_an_option_without_its_kind_or_a_bad_value_exits_2_saying_why(argv, said, capsys):
    parser = tail.build_parser()
    args = parser.parse_args(argv)
    with pytest.raises(SystemExit) as ended:
        apply_location_arguments(parser, args, follow=True)
    assert ended.value.code == 2
    assert said in capsys.readouterr().err


def test_convert_sorts_its_inputs_the_same_way():
    parser = convert.build_parser()
    args = parser.parse_args(["journal:nav", "chdb:///tmp/w", "a.log", "-o", "-"])
    apply_location_arguments(parser, args, follow=False, name="inputs")
    assert args.files == ["a.log"] and len(args.warehouses) == 1
    assert [journal.follow for journal in args.journals] == [False]
