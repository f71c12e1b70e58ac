"""Pilot tests of files in the app: open (dialog and start-up), progress, cancel, problems, save."""

from __future__ import annotations

import json
from pathlib import Path

from console_tui.model.formats.save import save_records
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record_batch import RecordColumns
from console_tui.ui.app import ConsoleApp
from console_tui.ui.screens.file_dialogs import OpenScreen, SaveScreen
from console_tui.ui.screens.load_problems import ProblemsScreen

from support.feed import records
from support.ui import line_with, screen_text, table_rows, type_text, until


def write_jsonl(path: Path, count: int, start: int = 0) -> list:
    rows = records(count, start)
    save_records(rows, path, "jsonl")
    return rows


def source_of(line: str) -> str:
    """The last column of a table row on the screen (the scrollbar's glyphs left out)."""
    return line.translate({ord(c): " " for c in "▁▂▃▄▅▆▇█"}).split()[-1]


def app_with(count: int) -> ConsoleApp:
    store = LogStore()
    store.extend_records(records(count))
    return ConsoleApp(store=store)


async def open_save_dialog(pilot, app: ConsoleApp) -> None:
    await pilot.press("s")
    await until(pilot, lambda: "Save messages to" in screen_text(app))


async def test_files_given_at_start_load_merged_with_their_source(tmp_path):
    first = write_jsonl(tmp_path / "a.jsonl", 50, start=0)
    second_rows = records(50, start=25)
    save_records(second_rows, tmp_path / "b.csv", "rqt")
    app = ConsoleApp(files=[str(tmp_path / "a.jsonl"), str(tmp_path / "b.csv")], utc=True)
    async with app.run_test(size=(160, 40)) as pilot:  # the newest rows reach back to the first file's
        await until(
            pilot, lambda: "100/100 shown" in screen_text(app) and not app.main.files.loading, what="both files"
        )
        await pilot.press("home")  # the oldest rows: the first file's alone, then both files' overlap
        await until(pilot, lambda: 1 in table_rows(app), what="the first rows")
        header = screen_text(app).splitlines()[app.main.table.region.y]
        assert "Source" in header, "files of different sources: the Source column is shown"
        rows = [line for _, (_, line) in sorted(table_rows(app).items())]
        times = [line.split()[1] for line in rows]
        assert times == sorted(times), "merged in time order"
        assert source_of(rows[0]) == "rosout", "JSON Lines keeps the recorded source"
        assert first[0].msg[:30] in rows[0]
        await pilot.press("end")
        await until(pilot, lambda: 100 in table_rows(app), what="the newest rows")
        rows = [line for _, (_, line) in sorted(table_rows(app).items())]
        assert {source_of(line) for line in rows} == {"rosout", "b.csv"}, "rows of both files"
        times = [line.split()[1] for line in rows]
        assert times == sorted(times)


async def test_open_dialog_loads_and_reports_problems(tmp_path):
    good = tmp_path / "good.jsonl"
    write_jsonl(good, 10)
    bad = tmp_path / "bad.csv"
    bad.write_bytes(b"\x00\x01\x02 binary garbage \xff\xfe")
    app = ConsoleApp(store=LogStore(), utc=True)
    async with app.run_test(size=(160, 30)) as pilot:
        await pilot.press("o")
        await until(pilot, lambda: "Open log files" in screen_text(app))
        assert isinstance(app.screen, OpenScreen)
        await type_text(pilot, f"{good} {bad}")
        await pilot.press("enter")
        await until(pilot, lambda: "10/10 shown" in screen_text(app) and not app.main.files.loading)
        await until(pilot, lambda: bool(app.main.files.problems))
        await pilot.press("exclamation_mark")
        assert isinstance(app.screen, ProblemsScreen)
        await pilot.pause()
        shown = screen_text(app)
        assert "1 problem while loading (Escape closes)" in shown
        problem_row = line_with(app, "bad.csv: binary data, not a log file")[1]
        assert "(first bytes: 00 01 02 20" in problem_row
        assert "good.jsonl" not in shown and "\x00" not in shown and "\x00" not in problem_row
        await pilot.press("escape")
        assert "problem while loading" not in screen_text(app)


async def test_open_dialog_refuses_a_missing_file(tmp_path):
    app = ConsoleApp(store=LogStore())
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.press("o")
        await until(pilot, lambda: "Open log files" in screen_text(app))
        await type_text(pilot, str(tmp_path / "nope.bag"))
        await pilot.press("enter")
        await until(pilot, lambda: "No such file: " in screen_text(app), what="the refusal")
        assert isinstance(app.screen, OpenScreen)
        await pilot.press("escape")
        assert not isinstance(app.screen, OpenScreen)
        assert "No such file" not in screen_text(app)


async def test_a_large_load_shows_progress_answers_keys_and_cancels(tmp_path, monkeypatch):
    """The load holds after its first batch until cancelled (10 s at most): a fast machine
    read all 300,000 lines before `x` reached it."""
    from console_tui.sources.files import loader

    load_records = loader.load_records

    def held_after_the_first_batch(files, cancel, **options):
        batches = load_records(files, cancel, **options)
        yield next(batches)
        cancel.wait(10)
        yield from batches

    monkeypatch.setattr(loader, "load_records", held_after_the_first_batch)
    big = tmp_path / "big.jsonl"
    with big.open("w") as stream:
        for i in range(300_000):
            stream.write(
                json.dumps(
                    {
                        "stamp_ns": i,
                        "level": 20,
                        "node": "n",
                        "msg": f"m{i}",
                        "file": "f",
                        "function": "g",
                        "line": 1,
                        "source": "s",
                    }
                )
                + "\n"
            )
    app = ConsoleApp(files=[str(big)])
    async with app.run_test(size=(160, 30)) as pilot:
        await until(pilot, lambda: len(app.main.store) > 0)
        assert app.main.load_bar.has_class("-loading")
        await pilot.press("up")  # keys work while loading
        await pilot.press("x")
        await until(pilot, lambda: not app.main.files.loading)
        assert 0 < len(app.main.store) < 300_000
        # The bar hides on the tick after the load ends.
        await until(pilot, lambda: not app.main.load_bar.has_class("-loading"), timeout=2, what="the load bar to hide")


async def test_save_what_is_shown_then_load_it_back(tmp_path):
    store = LogStore()
    store.extend_records(records(40))
    app = ConsoleApp(store=store, utc=True)
    target = tmp_path / "saved.jsonl"
    async with app.run_test(size=(120, 30)) as pilot:
        await open_save_dialog(pilot, app)
        assert isinstance(app.screen, SaveScreen)
        await pilot.press("end", "ctrl+u")
        await type_text(pilot, str(target))
        line_with(app, "saved.jsonl")  # the end of the path, as far as the box shows it
        await pilot.press("enter")
        await until(pilot, lambda: target.exists())
    again = ConsoleApp(files=[str(target)])
    async with again.run_test(size=(120, 30)) as pilot:
        await until(pilot, lambda: len(again.main.store) == 40 and not again.main.files.loading)
        original = [(r.stamp_ns, r.level, r.node, r.msg, r.file, r.function, r.line) for r in store]
        loaded = [(r.stamp_ns, r.level, r.node, r.msg, r.file, r.function, r.line) for r in again.main.store]
        assert loaded == original


async def test_save_dialog_marks_only_the_chosen_format():
    """The marks tell on from off without colour (NO_COLOR, monochrome terminals): only the
    chosen format shows ``●``, the others a blank."""
    app = app_with(3)
    async with app.run_test(size=(120, 30)) as pilot:
        await open_save_dialog(pilot, app)
        assert "▐●▌ rqt_console (ROS 2)" in line_with(app, "rqt_console (ROS 2)")[1]
        assert "▐ ▌ JSON Lines" in line_with(app, "JSON Lines")[1]
        assert "▐X▌ Only the rows shown" in line_with(app, "Only the rows shown")[1]
        await pilot.press("tab", "down", "down", "space")
        await until(pilot, lambda: "▐●▌ JSON Lines" in screen_text(app), what="the mark on the format clicked")
        assert "▐ ▌ rqt_console (ROS 2)" in line_with(app, "rqt_console (ROS 2)")[1]


async def test_save_to_a_missing_folder_is_refused_in_the_dialog(tmp_path):
    app = app_with(3)
    async with app.run_test(size=(120, 30)) as pilot:
        await open_save_dialog(pilot, app)
        await pilot.press("end", "ctrl+u")
        await type_text(pilot, str(tmp_path / "no" / "such" / "x.csv"))
        await pilot.press("enter")
        await until(pilot, lambda: "No such folder: " in screen_text(app), what="the refusal")
        assert isinstance(app.screen, SaveScreen)


async def test_with_live_records_waiting_the_files_come_first(tmp_path):
    """--live with files: live records wait until the files are in, so time order holds."""
    from console_tui.model.store.intake_queue import IntakeQueue

    write_jsonl(tmp_path / "old.jsonl", 500)
    live = IntakeQueue()
    live.put(RecordColumns.from_records(records(5, start=10_000)))  # newer than every file record, already waiting
    app = ConsoleApp(queue=live, files=[str(tmp_path / "old.jsonl")])
    async with app.run_test(size=(120, 30)) as pilot:
        await until(pilot, lambda: "505/505 shown" in screen_text(app), what="the file and the live records")
        stamps = [r.stamp_ns for r in app.main.store]
        assert stamps == sorted(stamps)
        rows = [line for _, (_, line) in sorted(table_rows(app).items())]
        times = [line.split()[1] for line in rows]
        assert max(table_rows(app)) == 505 and times == sorted(times), "the live records after the file's"


async def test_the_detail_view_says_when_a_file_gave_local_times(monkeypatch):
    """Issue 19: a ROS 1 Python log's times have no zone; the detail view says they were
    read as local time, and the other notes of the file's reading."""
    import time as clock

    from support.formats import DATA
    from support.ui import screen_text

    monkeypatch.setenv("TZ", "UTC")
    clock.tzset()
    master = DATA / "ros_log" / "c0ffee00-d4b2-11eb-9c3e-0242ac110002" / "master.log"
    app = ConsoleApp(files=[str(master)], utc=True)
    try:
        async with app.run_test(size=(160, 40)) as pilot:
            await until(pilot, lambda: len(app.main.store) == 3 and not app.main.files.loading)
            await until(pilot, lambda: "master.log" in app.main.files.source_notes)
            await pilot.press("enter")
            await pilot.pause()
            text = screen_text(app)
            assert "2021-06-24 05:23:16.950000000 +0000  (the file's local time: it gives no zone)" in text
            assert "File notes  its times are local times without a zone: read as this computer's local time" in text
    finally:
        monkeypatch.undo()
        clock.tzset()


async def test_a_run_folder_opens_merged_with_each_file_a_source(tmp_path, monkeypatch):
    """Issue 19: a ROS 1 run folder opens as every log in it, in time order, the file a column."""
    import os
    import shutil
    import time as clock

    from support.formats import DATA
    from support.ui import screen_text, toasts

    run = tmp_path / "run"
    shutil.copytree(DATA / "ros_log" / "c0ffee00-d4b2-11eb-9c3e-0242ac110002", run)
    os.utime(run / "rosout-1-stdout.log", ns=(1624512195_200_000_000,) * 2)
    (run / "params.yaml").write_text("a: 1\n")
    monkeypatch.setenv("TZ", "UTC")
    clock.tzset()
    app = ConsoleApp(files=[str(run)], utc=True)
    try:
        async with app.run_test(size=(200, 40), notifications=True) as pilot:
            await until(pilot, lambda: len(app.main.store) == 20 and not app.main.files.loading)
            await until(pilot, lambda: len(table_rows(app)) == 20, what="the 20 rows on the screen")
            text = screen_text(app)
            lines = text.splitlines()
            first = next(i for i, line in enumerate(lines) if "Checking log directory" in line)
            last = next(i for i, line in enumerate(lines) if "required process died" in line)
            assert first < last
            assert "roslaunch-robot-424" in lines[first] and "05:23:14.584" in lines[first]
            hello = [line for line in lines if "hello 1" in line]
            # In rosout.log and talker-2.log (rospy's own log): one row; talker-2-stdout.log
            # printed a line after it, which continues its message there: a row of its own.
            assert len(hello) == 2, "\n".join(hello)
            assert "rosout.log + talker" in hello[0] and "talker-2-stdout.log" in hello[1]
            skipped = "Loaded 20 records from 6 files, 2 repeats merged (1 other file in the folders passed over"
            await until(
                pilot, lambda: any(toast.startswith(skipped) for toast in toasts(app)), what=lambda: toasts(app)
            )
    finally:
        monkeypatch.undo()
        clock.tzset()
