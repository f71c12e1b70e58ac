"""The history on disk as the screen tells it: records dropped at the bound, a disk that fills
while chunks go to it (the session goes on in memory), a cache directory refused."""

from __future__ import annotations

import errno
import os

from console_tui.model.store.chunk_spill import ChunkSpill
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.spill_file import SpillFiles
from console_tui.ui.app import ConsoleApp

from support.feed import records
from support.ui import screen_text, until


def status_line(app) -> str:
    return screen_text(app).splitlines()[-2]


async def test_a_disk_that_fills_is_said_and_the_session_goes_on(tmp_path):
    full = {"now": False}

    def write(fd: int, data: bytes) -> int:
        if full["now"]:
            raise OSError(errno.ENOSPC, "No space left on device")
        return os.write(fd, data)

    spill = ChunkSpill(SpillFiles(tmp_path, min_free_bytes=0, write=write))
    store = LogStore(spill=spill, memory_bound=2 * CHUNK_SIZE)
    store.extend_records(records(CHUNK_SIZE + 10))
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(160, 24)) as pilot:
        full["now"] = True
        for start in range(CHUNK_SIZE + 10, 4 * CHUNK_SIZE, 2000):
            app.main.intake.add_records(records(2000, start=start))
        await until(pilot, lambda: "history in memory" in status_line(app), what=lambda: status_line(app))
        line = status_line(app)
        assert "dropped" in line and "No space left on device" in line
        assert f"{2 * CHUNK_SIZE:,}" in line  # what memory holds at most
        assert store.get(store.end_seq - 1).seq == store.end_seq - 1


async def test_records_dropped_at_the_bound_are_counted_on_the_status_line():
    store = LogStore(max_messages=500)
    store.extend_records(records(700))
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(160, 24)) as pilot:
        await until(pilot, lambda: "200 dropped" in status_line(app), what=lambda: status_line(app))


async def test_a_refused_directory_is_said(tmp_path):
    store = LogStore()
    store.memory_reason = f"{tmp_path} can be written by other users (mode 777)"
    store.extend_records(records(10))
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(200, 24)) as pilot:
        await until(pilot, lambda: "history in memory" in status_line(app), what=lambda: status_line(app))
        assert "can be written by other users" in status_line(app)
