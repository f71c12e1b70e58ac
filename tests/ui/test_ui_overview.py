"""The overview on screen: the timeline strip (an ERROR burst marked without colour, jumps
from a column by key and by click, the table's place), storms collapsed (10,000 identical
messages as one ``×10000`` row, expanded and collapsed again, collapsing off), the summary."""

from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.model.store.record_batch import RecordColumns
from console_tui.ui.app import ConsoleApp

from support.ui import line_with, screen_text, until

S = 1_000_000_000
BASE = 1_795_000_000 * S  # 11:06:40 UTC


def burst_store() -> LogStore:
    """100 s of INFO, ten a second, from three nodes, and 30 ERRORs at 50 s."""
    store = LogStore()
    records = []
    for i in range(1000):
        stamp = BASE + i * S // 10
        records.append(
            LogRecord(stamp_ns=stamp, level=20, node=("planner", "lidar", "battery")[i % 3], msg=f"tick {i}")
        )
        if i == 500:
            records.extend(
                LogRecord(stamp_ns=stamp + k * 1_000_000, level=40, node="tf", msg=f"lookup failed {k}")
                for k in range(30)
            )
    store.extend_records(records)
    return store


def strip_lines(app) -> list[str]:
    y = app.main.timeline_strip.region.y
    return screen_text(app).splitlines()[y : y + 4]


async def test_the_timeline_marks_an_error_burst_without_colour():
    app = ConsoleApp(store=burst_store(), utc=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "E" in strip_lines(app)[3], what="the timeline")
        label, _top, bottom, marks = strip_lines(app)
        # The span of the history, the column's duration and the peak rate, as words.
        assert label.startswith("11:06:40 ") and label.rstrip().endswith("11:08:20")
        assert "a column, peak" in label
        # One column marked E, in the middle; no other mark (only INFO elsewhere).
        width = len(marks.rstrip())
        assert width >= 90
        assert marks.count("E") == 1 and "W" not in marks and "F" not in marks
        column = marks.index("E")
        assert 0.45 * width <= column <= 0.55 * width
        # Bars everywhere (every column has messages), the burst's the tallest.
        assert all(cell != " " for cell in bottom[:width])
        assert strip_lines(app)[1][column] != " "
        # The table follows the tail: its place is the end of the axis.
        assert marks.rstrip().endswith("━")


async def test_a_key_or_a_click_on_a_column_shows_that_time_in_the_table():
    app = ConsoleApp(store=burst_store(), utc=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "E" in strip_lines(app)[3], what="the timeline")
        column = strip_lines(app)[3].index("E")
        assert "lookup failed" not in screen_text(app)
        await pilot.press("T")  # pick a column with the keys
        await pilot.press("home", *["right"] * column)
        await until(pilot, lambda: "E" in strip_lines(app)[0], what="the picked column's counts")
        assert "E30" in strip_lines(app)[0]  # the picked column: its time and counts
        await pilot.press("enter")
        await until(pilot, lambda: "lookup failed 0" in screen_text(app), what="the jump")
        _y, row = line_with(app, "lookup failed 0")
        assert "ERROR" in row and "11:07:30.000" in row
        assert "SCROLL" in screen_text(app).splitlines()[-2]
        assert app.main.table.cursor_seq is not None and app.main.store.get(app.main.table.cursor_seq).msg == "tick 500"
        # The table's place shows on the axis around the burst, no longer at the end.
        marks = strip_lines(app)[3]
        assert "━" in marks[column - 3 : column + 4] and not marks.rstrip().endswith("━")
        await pilot.press("escape", "end")
        await until(pilot, lambda: "lookup failed 0" not in screen_text(app), what="the tail again")
        # A click on the first column shows the first messages.
        await pilot.click("#timeline", offset=(0, 2))
        await until(pilot, lambda: "tick 0 " in screen_text(app), what="the click's jump")
        assert app.main.table.cursor_seq == 0


def storm_app(**options) -> ConsoleApp:
    store = LogStore()
    store.extend_records(
        LogRecord(stamp_ns=BASE + i * S, level=20, node="planner", msg=f"before {i}") for i in range(5)
    )
    store.extend_records(
        LogRecord(stamp_ns=BASE + 10 * S + i * 1000, level=30, node="tf", msg="Lookup would require extrapolation")
        for i in range(10_000)
    )
    return ConsoleApp(store=store, utc=True, **options)


async def test_ten_thousand_identical_messages_are_one_row_that_expands():
    app = storm_app()
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "×10000" in screen_text(app), what="the storm's row")
        _y, row = line_with(app, "×10000")
        assert "WARN" in row and "tf" in row and "11:06:50.000" in row  # first time
        assert "×10000 +10 ms" in row and "Lookup" in row  # to the last message, and the text
        assert screen_text(app).count("Lookup") == 1
        assert "1 storm" in screen_text(app).splitlines()[-2]
        assert app.main.table.row_count == 6
        # z on the storm's row expands it: every message a row, marked as the storm's.
        await pilot.press("z")
        await until(pilot, lambda: "▾×10000" in screen_text(app), what="the storm expanded")
        text = screen_text(app)
        assert text.count("┆ Lookup would require") >= 15
        assert app.main.table.row_count == 10_005
        await pilot.press("down", "down", "z")  # on one of its rows: collapsed again
        await until(pilot, lambda: "┆" not in screen_text(app), what="the storm collapsed")
        assert "×10000 +10 ms" in screen_text(app)
        assert app.main.table.row_count == 6


async def test_collapsing_off_shows_every_message():
    app = storm_app()
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "×10000" in screen_text(app), what="the storm's row")
        await pilot.press("Z")
        await until(pilot, lambda: "×" not in screen_text(app), what="collapsing off")
        text = screen_text(app)
        assert text.count("Lookup would require") >= 20
        assert "storms off" in text.splitlines()[-2]
        assert app.main.table.row_count == 10_005
        await pilot.press("Z")
        await until(pilot, lambda: "×10000" in screen_text(app), what="collapsing on again")


async def test_jumps_land_on_a_storms_row_and_go_on_past_it():
    app = storm_app()
    app.main.store.extend_records([LogRecord(stamp_ns=BASE + 30 * S, level=30, node="planner", msg="after the storm")])
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "×10000" in screen_text(app), what="the storm's row")

        def selected() -> str:
            return app.main.store.get(app.main.table.cursor_seq).msg

        await pilot.press("home", "w")  # the next WARN: the storm's first message
        await until(pilot, lambda: selected() == "Lookup would require extrapolation", what="the storm's row")
        await pilot.press("w")  # the next WARN after the storm, not one of its repeats
        await until(pilot, lambda: selected() == "after the storm", what="the WARN after the storm")
        await pilot.press("W")  # up again: the storm's last repeat shows in its row
        await until(pilot, lambda: selected() == "Lookup would require extrapolation", what="back to the storm")
        assert app.main.table.cursor_seq == 5
        line_with(app, "×10000")


async def test_storms_count_repeats_as_they_arrive():
    app = storm_app()
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "×10000" in screen_text(app), what="the storm's row")
        for batch in range(5):
            app.main.queue.put(
                RecordColumns.from_records(
                    [
                        LogRecord(
                            stamp_ns=BASE + 20 * S + (batch * 1000 + i) * 1000,
                            level=30,
                            node="tf",
                            msg="Lookup would require extrapolation",
                        )
                        for i in range(1000)
                    ]
                )
            )
        await until(pilot, lambda: "×15000" in screen_text(app), what="the count to grow")
        assert app.main.table.row_count == 6


async def test_the_timeline_hides_and_the_summary_jumps():
    app = ConsoleApp(store=burst_store(), utc=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "a column, peak" in screen_text(app), what="the timeline")
        await pilot.press("ctrl+t")
        await until(pilot, lambda: "a column, peak" not in screen_text(app), what="the timeline to hide")
        top = screen_text(app).splitlines()[0].split()
        assert top[:2] == ["#", "Time"] and {"Sev", "Node", "Message"} <= set(top)  # the table's header on top
        await pilot.press("ctrl+t", "S")
        await until(pilot, lambda: "Summary: 1,030 messages kept" in screen_text(app), what="the summary")
        text = screen_text(app)
        assert "11:06:40 to 11:08:19 (1.67 min)" in text
        _, error = line_with(app, "  ERROR")
        assert "30" in error and "11:07:30.000" in error and "tf: lookup failed 0" in error
        line_with(app, "Busiest nodes, last 60 s")
        planner = [[w for w in line.split() if w not in "█▊▎"] for line in text.splitlines() if " planner " in line]
        assert ["planner", "3.3/s"] in [words[:2] for words in planner]  # 200 messages in the last minute
        assert ["planner", "0", "334", "0", "0", "0", "334"] in [words[:7] for words in planner]
        await pilot.press("down", "enter")  # from INFO (the first with messages) to ERROR
        await until(pilot, lambda: "Summary:" not in screen_text(app), what="the summary to close")
        assert app.main.store.get(app.main.table.cursor_seq).msg == "lookup failed 0"
        line_with(app, "lookup failed 0")


async def test_the_summary_counts_the_nodes_first_in_slices(monkeypatch):
    """Nobody counted the nodes while their panel was closed: S counts them a slice at a time
    (the loop free between slices), then opens the summary with every message counted."""
    from console_tui.model.store.log_store import CHUNK_SIZE
    from console_tui.ui.controllers import overview

    monkeypatch.setattr(overview, "CATCH_UP_BUDGET_S", 0.0)  # one chunk a slice
    store = LogStore()
    store.extend_records(
        LogRecord(stamp_ns=BASE + i * 1_000_000, level=30, node="lidar" if i % 3 else "planner", msg=f"m {i}")
        for i in range(3 * CHUNK_SIZE)
    )
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(100, 30)) as pilot:
        assert not app.main.node_stats.counted
        await pilot.press("S")
        await until(pilot, lambda: "Summary: 12,288 messages kept" in screen_text(app), what="the summary")
        planner = [
            [w for w in line.split() if w not in "█▊▎"] for line in screen_text(app).splitlines() if " planner " in line
        ]
        assert ["planner", "0", "0", "4,096", "0", "0", "4,096"] in [words[:7] for words in planner]
