"""Narrowing a loaded run down (issue 28): on a 20,213-line ``rosout.log`` with 330 storms
of 50 repeats, every rule change recounts the storms and the timeline, the selected record
keeps its line on the screen, and the level keys compose."""

from __future__ import annotations

import random
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager

from textual.pilot import Pilot

from console_tui.ui.app import ConsoleApp

from support.storm_log import error_cycles, error_number, rows_before, write_storm_log
from support.ui import cursor_number, line_with, screen_text, table_rows, type_text, until

LINES = 20_213


def status(app) -> str:
    return screen_text(app).splitlines()[app.main.status_bar.region.y]


def strip_lines(app) -> list[str]:
    y = app.main.timeline_strip.region.y
    return screen_text(app).splitlines()[y : y + app.main.timeline_strip.region.height]


def settled(app) -> bool:
    """Every count caught up with the rules (the view, the storms, the timeline)."""
    return not (
        app.main.files.loading or app.main.view.refiltering or app.main.storms.behind or app.main.timeline.behind
    )


async def loaded(pilot, app) -> None:
    await until(pilot, lambda: f"{LINES:,}/{LINES:,} shown" in status(app) and settled(app), what="the file")


@asynccontextmanager
async def storm_log_loaded(tmp_path) -> AsyncIterator[tuple[ConsoleApp, Pilot]]:
    """The app at 100x30 with the storm log loaded (``support.storm_log``), every count done."""
    path = tmp_path / "rosout.log"
    assert write_storm_log(path) == LINES
    app = ConsoleApp(files=[str(path)], utc=True)
    async with app.run_test(size=(100, 30)) as pilot:
        await loaded(pilot, app)
        yield app, pilot


async def test_storms_and_the_timeline_are_recounted_after_every_rule_change(tmp_path):
    async with storm_log_loaded(tmp_path) as (app, pilot):
        # The load is over: the footer no longer offers to cancel it (the focus never moved).
        await until(pilot, lambda: "Cancel load" not in screen_text(app).splitlines()[-1], what="the footer")
        # (the status line says the counts at its next update, after the model settled)
        await until(pilot, lambda: "330 storms" in status(app), what="the storms on the status line")
        assert any("×50" in line for _, line in table_rows(app).values())
        full_label = strip_lines(app)[0]
        await pilot.press("2")  # hide INFO: no storm is left (each WARN says another plan)
        await until(pilot, lambda: "413/20,213 shown" in status(app) and settled(app), what="INFO hidden")
        await until(pilot, lambda: "storm" not in status(app), what="no storm on the status line")
        assert not any("×" in line for _, line in table_rows(app).values())
        assert "shown rows only" in strip_lines(app)[0] and strip_lines(app)[0] != full_label
        await pilot.press("2")  # INFO again: the same 330 storms, each one row
        await until(pilot, lambda: "20,213/20,213 shown" in status(app) and settled(app), what="INFO shown again")
        await until(pilot, lambda: "330 storms" in status(app), what="the storms again")
        rows = [line for _, line in table_rows(app).values()]
        assert any("×50" in line and "queue full in burst 329" in line for line in rows)
        assert sum("queue full in burst 329" in line for line in rows) == 1
        await pilot.press("2", "3", "4")  # every level in the file hidden
        await until(pilot, lambda: "0/20,213 shown" in status(app) and settled(app), what="every level hidden")
        strip = strip_lines(app)
        assert "no rows shown" in strip[0]
        assert not any(mark in "".join(strip) for mark in "EW▇█")
        await until(pilot, lambda: "storm" not in status(app), what="no storm on the status line")


async def test_the_selected_record_keeps_its_line_through_rule_changes(tmp_path):
    async with storm_log_loaded(tmp_path) as (app, pilot):
        cycle = error_cycles()[40]  # an ERROR far from either end: row 1,972 of 3,998
        number = error_number(cycle)
        await pilot.press("home", *["pagedown"] * (rows_before(cycle) // 24))
        while cursor_number(app) != number:
            await pilot.press("down")
        text = f"plan failed {cycle}"
        y = line_with(app, text)[0]
        for keys, shown in ((("2",), "413/"), (("2",), "20,213/"), (("3", "2"), "83/"), (("2", "3"), "20,213/")):
            await pilot.press(*keys)
            await until(pilot, lambda shown=shown: f"{shown}20,213 shown" in status(app) and settled(app))
            assert cursor_number(app) == number, f"after {keys}: the cursor left the ERROR"
            assert line_with(app, text)[0] == y, f"after {keys}: the ERROR moved on the screen"
        # A record the rules hide: the cursor goes to the shown record nearest in time.
        await pilot.press("up")  # the WARN of that cycle, 1 s before the ERROR
        warn = f"slow plan {cycle}"
        await until(pilot, lambda: cursor_number(app) == int(line_with(app, warn)[1].split()[0]))
        y = line_with(app, warn)[0]
        await pilot.press("3")  # WARN hidden: the ERROR 1 s later is nearer than the INFO 1.1 s before
        await until(pilot, lambda: "19,883/20,213 shown" in status(app) and settled(app))
        assert cursor_number(app) == number and line_with(app, text)[0] == y


async def test_the_minimum_level_never_shows_a_level_hidden_on_its_own(tmp_path):
    async with storm_log_loaded(tmp_path) as (app, pilot):
        await pilot.press("2")  # INFO hidden
        await until(pilot, lambda: "hiding INFO" in status(app) and settled(app))
        await pilot.press("greater_than_sign")  # the minimum above DEBUG: INFO stays hidden
        await until(pilot, lambda: "level≥WARN" in status(app) and settled(app))
        assert "413/20,213 shown" in status(app)
        assert not any(" INFO " in line for _, line in table_rows(app).values())
        await pilot.press("0", "3", "greater_than_sign")  # WARN hidden, then the minimum up: to INFO
        await until(pilot, lambda: "level≥INFO, hiding WARN" in status(app) and settled(app))
        assert "19,883/20,213 shown" in status(app)
        await pilot.press("greater_than_sign")  # past WARN (hidden already): ERROR
        await until(pilot, lambda: "level≥ERROR" in status(app) and settled(app))
        assert "83/20,213 shown" in status(app)
        assert {line.split()[2] for _, line in table_rows(app).values()} == {"ERROR"}


def on_row(app, text: str) -> bool:
    """Whether the cursor is on the row showing ``text`` (the # column names its record)."""
    number = next(word for word in line_with(app, text)[1].split() if word.isdigit())
    return app.main.table.cursor_seq == int(number) - 1


async def test_the_search_counts_rows_and_goes_row_to_row(tmp_path):
    async with storm_log_loaded(tmp_path) as (app, pilot):
        await pilot.press("f")
        await type_text(pilot, "/burst (30|31|32),/")
        await pilot.press("enter")
        what = "/burst (30|31|32),/"
        await until(
            pilot, lambda: f"match 3 of 3 {what}: in 3 rows, 150 messages" in status(app), what=lambda: status(app)
        )
        assert "×50" in line_with(app, "burst 32,")[1]
        assert on_row(app, "burst 32,")
        await pilot.press("N")
        await until(pilot, lambda: "match 2 of 3" in status(app), what=lambda: status(app))
        assert on_row(app, "burst 31,")
        await pilot.press("N")
        await until(pilot, lambda: "match 1 of 3" in status(app), what=lambda: status(app))
        await pilot.press("n")  # past burst 30's 49 repeats, to the next row holding a match
        await until(pilot, lambda: "match 2 of 3" in status(app), what=lambda: status(app))
        assert on_row(app, "burst 31,")
        await pilot.press("Z")  # storms not collapsed: every message a row
        await until(pilot, lambda: "of 150" in status(app) and "rows" not in status(app), what=lambda: status(app))


async def test_random_rule_changes_keep_the_selected_record_selected(tmp_path):
    """Level keys, ``>``/``<``, solo/mute of the row's node (the palette's), storms on and off, in a seeded
    random order: whenever the rules still show the selected record, it stays selected, on
    its line of the screen."""
    keys = ["1", "2", "3", "4", "greater_than_sign", "less_than_sign", "0", "Z", "solo_row_node", "mute_row_node"]
    async with storm_log_loaded(tmp_path) as (app, pilot):
        await pilot.press("home", *["pagedown"] * 80)
        chosen = random.Random(28)
        for _ in range(14):
            key = chosen.choice(keys)
            selected, line = app.main.table.cursor_seq, app.main.table.cursor_row - int(app.main.table.scroll_y)
            if "_" in key:  # the palette's actions on the row's node
                await app.run_action(key)
            else:
                await pilot.press(key)
            await until(pilot, lambda: settled(app), what=f"the rules after {key}")
            await pilot.pause()
            if selected is not None and app.main.view.row_shown(selected) is not None:
                number = f"{selected + 1} "
                assert app.main.table.cursor_seq == selected, f"{key}: the selected record lost"
                assert number in screen_text(app).splitlines()[app.main.table.region.y + 1 + line], f"{key}: moved"


async def test_the_palette_finds_what_a_person_types(tmp_path):
    async with storm_log_loaded(tmp_path) as (app, pilot):
        await pilot.press("ctrl+p")
        await type_text(pilot, "search")
        await until(pilot, lambda: "Clear the search" in screen_text(app), what="the palette's entries")
        lines = screen_text(app).splitlines()
        first = next(y for y, line in enumerate(lines) if "Find" in line or "Clear the search" in line)
        assert "Find" in lines[first], "the entry that starts a search comes before the one that ends it"
        await pilot.press("enter")  # Find: the search line, where the next letters go
        await type_text(pilot, "burst 7,")
        await until(pilot, lambda: "'burst 7,'" in status(app), what=lambda: status(app))
        assert "Save messages to" not in screen_text(app)
        await pilot.press("escape")
        await pilot.press("ctrl+p")
        await type_text(pilot, "editor")
        await until(pilot, lambda: "Open the source file" in screen_text(app), what="the editor's entry")
