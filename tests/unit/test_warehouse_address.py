"""Addresses of the log warehouse: what each scheme sends to or reads, and bad ones refused."""

from __future__ import annotations

import pytest

from console_tui.warehouse.address import CHDB, CLICKHOUSE, OTLP, AddressError, parse_address


def test_otlp_gets_its_path():
    assert parse_address("http://collector:4318").target == "http://collector:4318/v1/logs"
    assert parse_address("https://loki.example/otlp/v1/logs").target == "https://loki.example/otlp/v1/logs"
    assert parse_address("http://c:4318/").kind == OTLP


def test_clickhouse_forms_and_no_password_shown():
    address = parse_address("clickhouse://ops:s3cret@db.example:9000/fleet?table=robots_log")
    assert (address.kind, address.target, address.database, address.table) == (
        CLICKHOUSE,
        "http://db.example:9000",
        "fleet",
        "robots_log",
    )
    assert (address.user, address.password) == ("ops", "s3cret")
    assert "s3cret" not in address.text
    secure = parse_address("clickhouses://db.example/logs", {"CLICKHOUSE_PASSWORD": "pw"})
    assert (secure.target, secure.database, secure.table, secure.password) == (
        "https://db.example:8443",
        "logs",
        "otel_logs",
        "pw",
    )


def test_chdb_paths(tmp_path):
    address = parse_address(f"chdb://{tmp_path}/logs?table=t2")
    assert (address.kind, address.target, address.table) == (CHDB, f"{tmp_path}/logs", "t2")
    assert parse_address("chdb://./here").target.endswith("/here")


@pytest.mark.parametrize(
    "text",
    [
        "chdb://",
        "chdb:///x?table=drop table",
        "chdb:///x?color=red",
        "clickhouse:///db",
        "clickhouse://h/bad-name",
        "http://user:pw@c:4318",
        "ftp://x",
        "http://c:99999",
    ],
)
def test_bad_addresses_say_why(text):
    with pytest.raises(AddressError):
        parse_address(text)
