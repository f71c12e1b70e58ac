"""The log warehouse on each command's command line: a bad address exits 2 at once saying what
one looks like (``ship``, ``tail``, ``convert``, the app), ``--since``/``--until`` in every
form they take, and the headers ``ship`` sends a collector (``--header`` and
``OTEL_EXPORTER_OTLP_HEADERS``)."""

from __future__ import annotations

from datetime import datetime, timezone

import pytest

from console_tui import cli
from console_tui.commands import convert, ship, tail
from console_tui.commands.location_options import apply_location_arguments

NS = 1_000_000_000


def utc_ns(*fields: int) -> int:
    return int(datetime(*fields, tzinfo=timezone.utc).timestamp()) * NS


@pytest.mark.parametrize(
    ("main", "argv", "said"),
    [
        (ship.main, ["ftp://x"], "URL: 'ftp://x' is not http(s)://, clickhouse(s):// or chdb://"),
        (ship.main, ["clickhouse:///db"], "URL: a ClickHouse address names a host"),
        (ship.main, ["chdb://?table=t"], "URL: chdb:// needs a directory"),
        (tail.main, ["clickhouse://"], "a ClickHouse address names a host"),
        (tail.main, ["clickhouse://h:8123/db?tabel=x"], "unknown option 'tabel'"),
        (convert.main, ["chdb:///tmp/w?table=a-b", "-o", "-"], "table 'a-b' is not a plain name"),
        (convert.main, ["clickhouses://h:port/db", "-o", "-"], "not a ClickHouse address"),
        (cli.main, ["chdb://"], "chdb:// needs a directory"),
    ],
)
def test_a_bad_address_exits_2_saying_what_is_wrong(main, argv, said, capsys):
    with pytest.raises(SystemExit) as ended:
        main(argv)
    assert ended.value.code == 2
    err = capsys.readouterr().err
    assert said in err and "Traceback" not in err


@pytest.mark.parametrize(
    ("since", "until", "window"),
    [
        ("2026-12-05 02:50", "2026-12-05T03:00", (utc_ns(2026, 12, 5, 2, 50), utc_ns(2026, 12, 5, 3, 0))),
        ("2026-12-05T02:50:30", "2026-12-05 02:51", (utc_ns(2026, 12, 5, 2, 50, 30), utc_ns(2026, 12, 5, 2, 51))),
        ("1765000000", None, (1_765_000_000 * NS, None)),
    ],
)
def test_a_window_as_written(since, until, window):
    parser = tail.build_parser()
    args = parser.parse_args(["--utc", "--since", since, *(["--until", until] if until else []), "chdb:///tmp/w"])
    apply_location_arguments(parser, args, follow=True)
    assert (args.since_ns, args.until_ns) == window


def test_convert_reads_the_window_too():
    parser = convert.build_parser()
    args = parser.parse_args(["--since", "1765000000", "--until", "1765000060", "chdb:///tmp/w", "-o", "-"])
    apply_location_arguments(parser, args, follow=False, name="inputs")
    assert (args.since_ns, args.until_ns) == (1_765_000_000 * NS, 1_765_000_060 * NS)


def test_an_age_however_written_and_a_time_today():
    parser = tail.build_parser()
    ages = []
    for argv in (["--since", "2h"], ["--since=-2h"], ["--since=2h"]):
        args = parser.parse_args([*argv, "chdb:///tmp/w"])
        apply_location_arguments(parser, args, follow=True)
        ages.append(args.since_ns)
    assert max(ages) - min(ages) < 60 * NS  # the same age: journalctl's -2h as the query line's 2h
    args = parser.parse_args(["--utc", "--since", "02:50", "chdb:///tmp/w"])
    apply_location_arguments(parser, args, follow=True)
    assert datetime.fromtimestamp(args.since_ns / NS, timezone.utc).strftime("%H:%M:%S") == "02:50:00"


def test_ship_headers_from_the_environment_then_the_command_line():
    parser = ship.build_parser()
    environ = {
        "OTEL_EXPORTER_OTLP_HEADERS": "Authorization=Bearer%20abc,x-team=nav, x-empty= ,junk",
        "OTEL_EXPORTER_OTLP_LOGS_HEADERS": "x-team=logs",
    }
    assert ship.request_headers(parser, [], environ) == {
        "Authorization": "Bearer abc",  # URL-encoded in the variable, as the standard says
        "x-team": "logs",  # the logs' own variable wins
        "x-empty": "",
    }
    given = ["x-team=arm", "X-Key=a=b", " spaced =1"]
    assert ship.request_headers(parser, given, environ) == {
        "Authorization": "Bearer abc",
        "x-team": "arm",  # the command line wins
        "x-empty": "",
        "X-Key": "a=b",  # as given: the first = splits
        "spaced": "1",
    }
    assert ship.request_headers(parser, [], {}) == {}


@pytest.mark.parametrize("bad", ["novalue", "=value"])
def test_a_header_without_its_name_or_value_exits_2(bad, capsys):
    with pytest.raises(SystemExit) as ended:
        ship.request_headers(ship.build_parser(), [bad], {})
    assert ended.value.code == 2
    assert f"--header: expected K=V, got {bad!r}" in capsys.readouterr().err
