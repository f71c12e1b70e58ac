"""The history on disk as the screen tells it: records dropped at the bound, a disk that fills
while chunks go to it (the session goes on in memory), a cache directory refused."""

from __future__ import annotations

import errno
import os

from console_tui.model.store.chunk_spill import ChunkSpill
from console_tui.model.store.history_dir import open_session_spill
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.spill_file import SpillFiles
from console_tui.ui.app import ConsoleApp

from support.feed import records
from support.ui import cursor_line, cursor_number, line_with, screen_text, type_text, until


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
    shared = tmp_path / "history"
    shared.mkdir()
    os.chmod(shared, 0o777)  # anyone may write here, and no sticky bit
    spill, _, why = open_session_spill(shared)
    assert spill is None
    store = LogStore(spill=spill)
    store.memory_reason = why  # as the command makes its store
    store.extend_records(records(10))
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(200, 24)) as pilot:
        await until(pilot, lambda: "history in memory" in status_line(app), what=lambda: status_line(app))
        assert f"{shared} can be written by other users (mode 777)" in status_line(app)


async def test_the_whole_history_on_disk_is_reached_by_keys_rules_search_and_the_node_panel(tmp_path):
    """Six chunks on disk (two of them kept in memory), the oldest two dropped at the bound:
    Home goes to the oldest kept, a level key and a search go over all of it, the node panel
    counts all of it."""
    made = records(8 * CHUNK_SIZE + 100)
    made[2 * CHUNK_SIZE + 5].msg = "the far needle"
    store = LogStore(6 * CHUNK_SIZE + 100, spill=ChunkSpill(SpillFiles(tmp_path, min_free_bytes=0), warm_chunks=2))
    store.extend_records(made)
    assert store.first_seq == 2 * CHUNK_SIZE and store.on_disk >= 5 * CHUNK_SIZE
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(120, 30)) as pilot:
        dropped = f"{store.evicted:,} dropped"  # the bound on disk (--max-messages), said
        await until(pilot, lambda: dropped in status_line(app), what=lambda: status_line(app))
        await pilot.press("home")
        await until(pilot, lambda: cursor_number(app) == store.first_seq + 1, what=lambda: status_line(app))
        assert made[store.first_seq].msg[:30] in (cursor_line(app) or "")
        await pilot.press("end")
        await until(pilot, lambda: cursor_number(app) == store.end_seq, what=lambda: status_line(app))
        await pilot.press("f")
        await type_text(pilot, "far needle")
        await pilot.press("enter")
        await until(pilot, lambda: "match 1 of 1 'far needle'" in status_line(app), what=lambda: status_line(app))
        line = cursor_line(app) or ""
        assert "the far needle" in line and str(2 * CHUNK_SIZE + 6) in line.split()[:2]  # (after the match's mark)
        await pilot.press("escape", "2")  # INFO hidden over the whole history
        kept = made[store.first_seq :]
        shown = sum(1 for rec in kept if rec.level != 20)
        await until(pilot, lambda: f"{shown:,}/{len(kept):,} shown" in status_line(app), what=lambda: status_line(app))
        await pilot.press("home")
        first = store.first_seq + next(i for i, rec in enumerate(kept) if rec.level != 20)
        await until(pilot, lambda: cursor_number(app) == first + 1, what=lambda: status_line(app))
        await pilot.press("ctrl+n")
        await until(pilot, lambda: "Nodes: 5" in screen_text(app) and "counting" not in screen_text(app))
        lidar = sum(1 for rec in kept if rec.node == "sensors.lidar_driver")
        _, row = line_with(app, "sensors.lidar_driver")
        assert sum(map(int, row.split("▏")[1].split()[1:6])) == lidar  # its D, I, W, E and F
