"""chDB in a child process (``warehouse/chdb_process.py``): the engine's memory and crashes
stay out of the console's process; a second process on the same directory, a child killed and
a child that stops answering are each a ``WarehouseError`` that says so, and the next client
works again."""

from __future__ import annotations

import os
import signal

import pytest

from console_tui.model.store.record import LogRecord
from console_tui.warehouse import chdb_process
from console_tui.warehouse.chdb_process import ChdbProcess
from console_tui.warehouse.clickhouse import TableClient, WarehouseError

from support.warehouse import chdb_address, needs_store, ship_records, table_client

pytestmark = needs_store

COUNT = "SELECT count() FROM default.otel_logs"


def child_of(client: TableClient) -> int:
    engine = client._client
    assert isinstance(engine, ChdbProcess) and engine._process is not None
    return engine._process.pid


def test_the_engine_runs_in_a_child_that_ends_with_the_client(tmp_path):
    address = chdb_address(tmp_path)
    ship_records(address, [LogRecord(1_765_000_000_000_000_000 + i, 20, "n", f"m{i}") for i in range(3)])
    client = TableClient(address)
    pid = child_of(client)
    assert pid != os.getpid() and client.value(COUNT) == 3
    with pytest.raises(WarehouseError, match="another process"):
        TableClient(address)  # one process at a time: the child has it
    client.close()
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)  # ended, and the directory free again:
    with table_client(address) as again:
        assert again.value(COUNT) == 3


def test_a_child_killed_or_silent_is_said_and_the_next_client_works(tmp_path, monkeypatch):
    address = chdb_address(tmp_path)
    with table_client(address) as client:
        client.create_table()
        os.kill(child_of(client), signal.SIGKILL)
        with pytest.raises(WarehouseError, match=r"the chDB process ended \(exit status -9"):
            client.value(COUNT)
        with pytest.raises(WarehouseError, match="was closed"):
            client.value(COUNT)
    monkeypatch.setattr(chdb_process, "ANSWER_MARGIN_S", 0.0)
    client = TableClient(address, timeout=1.0)
    try:
        os.kill(child_of(client), signal.SIGSTOP)
        with pytest.raises(WarehouseError, match="did not answer within 1 s"):
            client.value(COUNT)
    finally:
        client.close()
    with table_client(address) as again:
        assert again.value(COUNT) == 0
