"""The table ``otel_logs`` in ClickHouse (its HTTP interface) or chDB (its engine, in a child
process: ``chdb_process.py``), through one client, clickhouse-connect: the DDL, inserts and
queries run on ClickHouse itself either way.

Every query is bounded: in time (``max_execution_time`` on the server, the connection's own
timeouts) and in rows (the caller's ``LIMIT``; ``max_result_rows`` as a second fence). chDB
lets one process at a time open a directory: a second one is told so in words.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any
from urllib.parse import urlsplit

from .address import CHDB, Address
from .chdb_process import ChdbProcess
from .driver import clickhouse_driver, describe
from .outcome import TAKEN, Outcome, WarehouseError
from .schema import INSERT_COLUMNS, create_table_sql, quoted

#: How long one query or insert may run, in seconds.
QUERY_TIMEOUT_S = 20.0
#: How long connecting may take.
CONNECT_TIMEOUT_S = 5.0
#: No query returns more rows than this, whatever its LIMIT says.
MAX_RESULT_ROWS = 2_000_000


class TableClient:
    """One connection to the warehouse's table (not shared between threads)."""

    def __init__(self, address: Address, *, timeout: float = QUERY_TIMEOUT_S, create: bool = False) -> None:
        """``create``: a chDB directory is made when missing (for shipping; reading needs one)."""
        self.address = address
        self.timeout = timeout
        self.table = f"{quoted(address.database)}.{quoted(address.table)}"
        settings: dict[str, Any] = {"max_execution_time": int(max(timeout, 1)), "max_result_rows": MAX_RESULT_ROWS}
        settings["result_overflow_mode"] = "break"
        try:
            if address.kind == CHDB:
                if create:
                    os.makedirs(address.target, exist_ok=True)
                elif not os.path.isdir(address.target):
                    raise WarehouseError(f"no such directory: {address.target}")
                self._client = ChdbProcess(address.target, settings=settings, timeout=timeout)
            else:
                parts = urlsplit(address.target)
                self._client = clickhouse_driver().get_client(
                    host=parts.hostname,
                    port=parts.port,
                    secure=parts.scheme == "https",
                    username=address.user or None,
                    password=address.password,
                    database=None,
                    connect_timeout=CONNECT_TIMEOUT_S,
                    send_receive_timeout=timeout,
                    settings=settings,
                )
        except WarehouseError:
            raise
        except Exception as error:  # the driver's and the engine's, of every kind
            raise WarehouseError(describe(error)) from None

    def lazy_rows(self, limit: int) -> str:
        """The SETTINGS clause that reads a row's heavy columns only for the ``limit`` rows an
        ``ORDER BY ... LIMIT`` keeps, on an engine that can (ClickHouse 25.5 and later); else ""."""
        try:
            major, minor = (int(part) for part in str(self._client.server_version).split(".")[:2])
        except (AttributeError, ValueError):
            return ""
        if (major, minor) < (25, 5):
            return ""
        return f" SETTINGS query_plan_max_limit_for_lazy_materialization = {int(limit)}"

    def close(self) -> None:
        try:
            self._client.close()
        except Exception:
            pass

    def create_table(self) -> None:
        """The database and the table, with the exporter's DDL, when they are missing."""
        try:
            if self.address.database != "default":
                self._client.command(f"CREATE DATABASE IF NOT EXISTS {quoted(self.address.database)}")
            self._client.command(create_table_sql(self.address.database, self.address.table))
        except Exception as error:
            raise WarehouseError(describe(error)) from None

    def insert(self, rows: Sequence[Sequence[Any]], token: str = "") -> Outcome:
        """Insert rows of ``INSERT_COLUMNS``; ``token`` lets a replicated table drop a batch sent
        twice (``insert_deduplication_token``). Any failure is tried again later."""
        settings = {"insert_deduplication_token": token} if token else None
        try:
            self._client.insert(
                self.table, list(rows), column_names=list(INSERT_COLUMNS), database=None, settings=settings
            )
        except Exception as error:
            return Outcome(False, retry=True, problem=describe(error))
        return TAKEN

    def columns(self, sql: str) -> list[Sequence[Any]]:
        """The result of a query, column by column; ``WarehouseError`` if it fails."""
        try:
            result = self._client.query(sql)
            return list(result.result_columns)
        except Exception as error:
            raise WarehouseError(describe(error)) from None

    def value(self, sql: str) -> Any:
        columns = self.columns(sql)
        return columns[0][0] if columns and len(columns[0]) else None
