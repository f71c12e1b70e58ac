"""Where the log warehouse is: an address as the command line gives it.

    http://collector:4318           OTLP over HTTP (``/v1/logs`` added when there is no path)
    https://otlp.example.com/otlp   (Loki 3 takes ``/otlp/v1/logs``: give the whole path)
    clickhouse://user:pw@host:8123/logs?table=otel_logs   ClickHouse's HTTP interface
    clickhouses://host/logs         the same over TLS (port 8443 by default)
    chdb:///var/lib/console-tui/logs   chDB: ClickHouse's engine on a local directory

``parse_address`` reads one (``AddressError`` says what is wrong); ``Address.text`` is how it
is shown (never the password). The user and password of ClickHouse may also come from
``CLICKHOUSE_USER`` and ``CLICKHOUSE_PASSWORD``.
"""

from __future__ import annotations

import os
import re
from collections.abc import Mapping
from dataclasses import dataclass
from urllib.parse import parse_qs, unquote, urlsplit

OTLP, CLICKHOUSE, CHDB = "otlp", "clickhouse", "chdb"
#: The schemes of the warehouse the console can read (OTLP can only be sent to).
READABLE_SCHEMES = ("clickhouse://", "clickhouses://", "chdb://")
SHIPPABLE_SCHEMES = ("http://", "https://", *READABLE_SCHEMES)
DEFAULT_TABLE = "otel_logs"
DEFAULT_DATABASE = "default"
OTLP_LOGS_PATH = "/v1/logs"
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,63}")


class AddressError(ValueError):
    """An address that is not one of the warehouse's; the text says what one looks like."""


@dataclass(frozen=True)
class Address:
    """A parsed warehouse address."""

    kind: str
    #: OTLP: the whole URL to POST to; ClickHouse: ``http(s)://host:port``; chDB: the directory.
    target: str
    database: str = DEFAULT_DATABASE
    table: str = DEFAULT_TABLE
    user: str = ""
    password: str = ""
    #: As given, without the password: what the status line and messages show.
    text: str = ""

    @property
    def readable(self) -> bool:
        return self.kind != OTLP

    def short_text(self, limit: int = 48) -> str:
        """``text`` in at most ``limit`` characters: a long directory's end kept."""
        if len(self.text) <= limit:
            return self.text
        scheme, _, rest = self.text.partition("://")
        return f"{scheme}://…{rest[-(limit - len(scheme) - 4) :]}"


def is_warehouse(text: str) -> bool:
    """Whether a positional argument names the warehouse (``clickhouse://``, ``chdb://``...)."""
    return text.lower().startswith(READABLE_SCHEMES)


def parse_address(text: str, environ: Mapping[str, str] | None = None) -> Address:
    """The address ``text`` names; ``AddressError`` if it names none."""
    env = os.environ if environ is None else environ
    lowered = text.lower()
    if lowered.startswith("chdb://"):
        return _chdb(text)
    if lowered.startswith(("clickhouse://", "clickhouses://")):
        return _clickhouse(text, env)
    if lowered.startswith(("http://", "https://")):
        return _otlp(text)
    raise AddressError(
        f"not a log warehouse address: {text!r} (http(s)://collector:4318 for OTLP, "
        "clickhouse(s)://host:8123/database, chdb:///directory)"
    )


def _options(query: str, where: str) -> tuple[str, str]:
    """``?table=...&database=...`` -> (database or "", table)."""
    options = parse_qs(query, keep_blank_values=True)
    unknown = sorted(set(options) - {"table", "database"})
    if unknown:
        raise AddressError(f"{where}: unknown option {unknown[0]!r} (options: table, database)")
    table = options.get("table", [DEFAULT_TABLE])[-1]
    database = options.get("database", [""])[-1]
    for name, value in (("table", table), ("database", database)):
        if value and not _NAME.fullmatch(value):
            raise AddressError(f"{where}: {name} {value!r} is not a plain name (letters, digits, _)")
    return database, table


def _chdb(text: str) -> Address:
    rest = text[len("chdb://") :]
    path, _, query = rest.partition("?")
    if not path:
        raise AddressError("chdb:// needs a directory: chdb:///var/lib/logs (or chdb://./logs)")
    database, table = _options(query, "chdb")
    directory = os.path.abspath(os.path.expanduser(unquote(path)))
    options = [
        f"{name}={value}"
        for name, value in (("database", database), ("table", table))
        if value and value not in (DEFAULT_DATABASE, DEFAULT_TABLE)
    ]
    shown = f"chdb://{directory}" + (f"?{'&'.join(options)}" if options else "")
    return Address(CHDB, directory, database or DEFAULT_DATABASE, table, text=shown)


def _clickhouse(text: str, env: Mapping[str, str]) -> Address:
    try:
        parts = urlsplit(text)
        port = parts.port
    except ValueError as error:
        raise AddressError(f"not a ClickHouse address: {text!r} ({error})") from None
    if not parts.hostname:
        raise AddressError(f"a ClickHouse address names a host: clickhouse://host:8123/database, got {text!r}")
    secure = parts.scheme.lower() == "clickhouses"
    path_database = parts.path.strip("/")
    option_database, table = _options(parts.query, "clickhouse")
    database = option_database or path_database or DEFAULT_DATABASE
    if not _NAME.fullmatch(database):
        raise AddressError(f"clickhouse: database {database!r} is not a plain name (letters, digits, _)")
    port = port or (8443 if secure else 8123)
    host = parts.hostname if ":" not in parts.hostname else f"[{parts.hostname}]"
    user = unquote(parts.username or "") or env.get("CLICKHOUSE_USER", "")
    password = unquote(parts.password or "") or env.get("CLICKHOUSE_PASSWORD", "")
    scheme = "https" if secure else "http"
    shown = f"{parts.scheme}://{f'{user}@' if user else ''}{host}:{port}/{database}"
    if table != DEFAULT_TABLE:
        shown += f"?table={table}"
    return Address(CLICKHOUSE, f"{scheme}://{host}:{port}", database, table, user, password, shown)


def _otlp(text: str) -> Address:
    try:
        parts = urlsplit(text)
        parts.port  # noqa: B018 - a bad port raises here
    except ValueError as error:
        raise AddressError(f"not an OTLP address: {text!r} ({error})") from None
    if not parts.hostname:
        raise AddressError(f"an OTLP address names a host: http://collector:4318, got {text!r}")
    if parts.username or parts.password:
        raise AddressError("give an OTLP endpoint's credentials with --header (Authorization=...), not in the URL")
    path = parts.path if parts.path not in ("", "/") else OTLP_LOGS_PATH
    url = f"{parts.scheme.lower()}://{parts.netloc}{path}" + (f"?{parts.query}" if parts.query else "")
    return Address(OTLP, url, text=url)
