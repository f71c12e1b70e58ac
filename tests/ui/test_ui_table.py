"""Pilot tests of the table: follow, scroll, pause, resume, clear, details, help, columns.
Keys are pressed as a person does and the screen is read back (``support.ui``)."""

from __future__ import annotations

import pytest

from console_tui.ui.widgets.log_table import LogTable

from support.feed import records
from support.ui import (
    cursor_number,
    frame_drawn,
    line_with,
    make_app,
    screen_text,
    style_at,
    table_rows,
    type_text,
    until,
)


def status_line(app) -> str:
    """The status bar: the terminal's last row but one."""
    return screen_text(app).splitlines()[-2]


def bottom_number(app) -> int:
    return max(table_rows(app))


async def test_follows_the_tail_as_records_arrive():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        await until(pilot, lambda: cursor_number(app) == 100, what="the cursor on the last row")
        assert bottom_number(app) == 100 and "FOLLOW" in status_line(app)
        app.main.intake.add_records(records(50, start=100))
        await until(pilot, lambda: "150/150 shown" in status_line(app), what="the new records counted")
        await until(pilot, lambda: cursor_number(app) == 150, what="the cursor following the tail")
        assert bottom_number(app) == 150 and "FOLLOW" in status_line(app)


async def test_moving_up_stops_following_and_keeps_the_rows_in_place():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.press("up", "up", "up")
        await until(pilot, lambda: cursor_number(app) == 97 and "SCROLL" in status_line(app), what="SCROLL")
        rows = {number: y for number, (y, _) in table_rows(app).items()}
        app.main.intake.add_records(records(50, start=100))
        await until(pilot, lambda: "150/150 shown" in status_line(app), what="the new records counted")
        assert {number: y for number, (y, _) in table_rows(app).items()} == rows, "the same rows in the same places"
        assert cursor_number(app) == 97 and "SCROLL" in status_line(app)
        await pilot.press("end")
        await until(pilot, lambda: cursor_number(app) == 150, what="the cursor on the newest row")
        assert bottom_number(app) == 150 and "FOLLOW" in status_line(app)


async def test_rows_arriving_below_the_screen_redraw_only_the_scrollbar():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        table = app.main.table
        await pilot.press("pageup")
        await until(pilot, lambda: "SCROLL" in status_line(app), what="SCROLL")
        drawn = []
        draw = table.render_line
        table.render_line = lambda y: drawn.append(y) or draw(y)
        rows_before = {number: line[:-2] for number, (_, line) in table_rows(app).items()}  # less the scrollbar
        thumb_before = thumb_rows(app)
        drawn.clear()
        app.main.intake.add_records(records(500, start=100))
        await until(pilot, lambda: "600/600 shown" in status_line(app), what="the new records counted")
        # The scrollbar follows within a tenth of a second: its thumb drawn smaller and higher
        # is the frame that would draw the rows again, had they changed.
        await until(pilot, lambda: thumb_rows(app) != thumb_before, what="the scrollbar following the new rows")
        await frame_drawn(pilot, table.vertical_scrollbar)
        assert len(thumb_rows(app)) < len(thumb_before) and min(thumb_rows(app)) < min(thumb_before)
        assert drawn == []  # no row drawn again: the same rows, the same strips
        assert {number: line[:-2] for number, (_, line) in table_rows(app).items()} == rows_before
        await pilot.press("end")
        await until(pilot, lambda: cursor_number(app) == 600, what="the cursor on the newest row")
        assert bottom_number(app) == 600 and "FOLLOW" in status_line(app)


def thumb_rows(app) -> list[int]:
    """The screen rows where the table's scrollbar shows its thumb (drawn in reverse)."""
    region = app.main.table.region
    return [y for y in range(region.y, region.bottom) if style_at(app, region.right - 1, y).reverse]


async def test_the_scrollbar_stays_at_the_bottom_while_following_and_is_not_redrawn():
    app = make_app(1000)
    async with app.run_test(size=(100, 24)) as pilot:
        await until(pilot, lambda: "1,000/1,000 shown" in status_line(app), what="the records shown")
        bottom = app.main.table.region.bottom - 1
        assert thumb_rows(app) == [bottom]
        bar = app.main.table.vertical_scrollbar
        painted = []
        paint = bar.render
        bar.render = lambda: painted.append(1) or paint()
        for start in range(1000, 20_000, 1000):
            app.main.intake.add_records(records(1000, start=start))
            await pilot.pause()
        await until(pilot, lambda: "20,000/20,000 shown" in status_line(app), what="the new records shown")
        # The scrollbar given the 20,000 rows (within a tenth of a second), then the frame
        # after its check whether the thumb moved: a repaint would have come by then.
        table = app.main.table
        await until(pilot, lambda: bar.window_virtual_size == table.virtual_size.height, what="the scrollbar's size")
        assert table.virtual_size.height == 20_001
        await frame_drawn(pilot, bar)
        assert thumb_rows(app) == [bottom], "the thumb left the bottom while the table follows the tail"
        assert painted == [], "the scrollbar was drawn again with its thumb in the same place"
        await pilot.press("home")
        await until(pilot, lambda: cursor_number(app) == 1, what="the first row")
        top = [[table.region.y + 1], [table.region.y]]
        await until(pilot, lambda: thumb_rows(app) in top, what=lambda: f"the thumb at the top, not {thumb_rows(app)}")


async def test_position_survives_eviction_at_the_bound():
    app = make_app(100, max_messages=120)
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.press("pageup", "pageup")  # past the first screen (the timeline takes rows)
        await until(pilot, lambda: "SCROLL" in status_line(app), what="SCROLL")
        await until(pilot, lambda: (cursor_number(app) or 100) < 80, what="the cursor two pages up")
        cursor = cursor_number(app)
        assert cursor is not None and cursor > 10
        app.main.intake.add_records(records(30, start=100))
        await until(pilot, lambda: "120/120 shown" in status_line(app), what="the oldest 10 evicted")
        assert cursor_number(app) == cursor, "the cursor stays on its record"
        assert cursor + 1 in table_rows(app) and min(table_rows(app)) > 10


async def test_pause_freezes_the_view_counts_new_and_resume_catches_up():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.press("space")
        await until(pilot, lambda: "PAUSED" in status_line(app), what="PAUSED")
        app.main.intake.add_records(records(50, start=100))
        await until(pilot, lambda: "+50 new" in status_line(app), what="+50 new")
        assert bottom_number(app) == 100 and cursor_number(app) == 100, "the view frozen"
        assert "space Resume" in screen_text(app).splitlines()[-1]
        await pilot.press("space")
        await until(pilot, lambda: cursor_number(app) == 150, what="the view caught up")
        assert bottom_number(app) == 150 and "PAUSED" not in status_line(app) and "150/150 shown" in status_line(app)


async def test_clear_empties_the_view_and_numbering_goes_on():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.press("c")
        await until(pilot, lambda: "0/0 shown" in status_line(app), what="the cleared view")
        assert table_rows(app) == {}, "no row left on the screen"
        app.main.intake.add_records(records(3, start=500))
        await until(pilot, lambda: "3/3 shown" in status_line(app), what="three new rows")
        assert list(table_rows(app)) == [101, 102, 103], "numbering goes on after a clear"
        assert cursor_number(app) == 103


def field(app, name: str) -> str:
    """The value of one field of the details on the screen."""
    line = line_with(app, f"█ {name} ")[1]
    return line.split(f"█ {name} ", 1)[1].rstrip(" █").split("█")[0].strip()


async def test_enter_opens_details_with_every_field_and_steps():
    app = make_app(20)
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.press("up", "up", "enter")
        await until(pilot, lambda: "n Next row" in screen_text(app), what="the details")
        assert field(app, "#") == "18"
        assert field(app, "Stamp") == "1795000002.329000000"
        assert field(app, "Node") == "navigation.planner.costmap"
        assert field(app, "File") == "/opt/robot/src/costmap.cpp"
        assert field(app, "Function") == "on_timer" and field(app, "Line") == "159"
        assert field(app, "Severity") == "INFO (20)" and field(app, "Source") == "/rosout"
        assert "temperature: 41.2 C" in line_with(app, " 2    temperature")[1], "the message, line by line"
        await pilot.press("n")
        await until(pilot, lambda: field(app, "#") == "19", what="the next row's details")
        await pilot.press("p", "p")
        await until(pilot, lambda: field(app, "#") == "17", what="two rows back")
        await pilot.press("escape")
        await until(pilot, lambda: "n Next row" not in screen_text(app), what="the details closed")
        assert cursor_number(app) == 17, "the table's cursor went with the details"


async def test_double_click_opens_details():
    app = make_app(10)
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.click(LogTable, offset=(20, 3), times=2)
        await until(pilot, lambda: "n Next row" in screen_text(app), what="the details")
        assert field(app, "#") == "3", "the row clicked (the header is row 0)"


async def changes(pilot, condition, within: float = 1.0) -> bool:
    """Whether ``condition()`` comes to hold within ``within`` seconds (a page that may not move)."""
    try:
        await until(pilot, condition, timeout=within)
    except AssertionError:
        return False
    return True


def words_on_screen(app) -> list[str]:
    """The screen's rows with each run of spaces (and the dialog's border) made one space."""
    return [" ".join(line.replace("█", " ").split()) for line in screen_text(app).splitlines()]


async def test_help_lists_keys_and_closes():
    app = make_app(5)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("question_mark")
        await until(pilot, lambda: any("space Pause" in line for line in words_on_screen(app)[:-1]), what="the help")
        first_page = words_on_screen(app)
        pages = [first_page]
        for _ in range(10):  # page down to the end, as a person reads it
            await pilot.press("pagedown")
            if not await changes(pilot, lambda: words_on_screen(app) != pages[-1]):
                break
            pages.append(words_on_screen(app))
        assert len(pages) > 1, "more keys than one screen: the help scrolls"
        seen = [line for page in pages for line in page]
        for row in ("↑, k Up", "end, G Follow tail", "space Pause", "c Clear", "/ Query", "?, f1 Help"):
            assert any(line.endswith(row) or f" {row} " in f" {line} " for line in seen), row
        for row in ("a Add rule", "y Copy message", "^p Command palette"):
            assert any(row in line for line in seen), row
        assert any("space Pause" in line for line in first_page[:-1]), "the table's keys come first"
        await pilot.press("escape")
        await until(
            pilot,
            lambda: not any("space Pause" in line for line in words_on_screen(app)[:-1]),
            what="the help closed: only the footer names keys",
        )


def header(app) -> str:
    """The table's header row on the screen."""
    return screen_text(app).splitlines()[app.main.table.region.y]


async def test_columns_can_be_hidden_and_shown():
    app = make_app(5)
    async with app.run_test(size=(160, 30)) as pilot:
        await until(pilot, lambda: "Function" in header(app), what="the header")
        assert "Source" not in header(app)
        await pilot.press("C")
        await until(pilot, lambda: "Columns shown" in screen_text(app), what="the columns dialog")
        # The list ends: ..., Function, Line, Source.
        await pilot.press("end", "space", "up", "up", "space", "enter")
        await until(pilot, lambda: "Columns shown" not in screen_text(app), what="the dialog closed")
        assert "Function" not in header(app) and "Source" in header(app)
        assert table_rows(app)[1][1].split()[-1] == "rosout", "the Source column's values"
        await pilot.press("C")
        await until(pilot, lambda: "Columns shown" in screen_text(app), what="the columns dialog")
        await pilot.press("end", "space", "escape")  # cancelled: nothing changes
        await until(pilot, lambda: "Columns shown" not in screen_text(app), what="the dialog closed")
        assert "Function" not in header(app) and "Source" in header(app)


@pytest.mark.parametrize("width", [60, 80, 120, 200])
async def test_narrow_terminals_keep_severity_node_and_message(width):
    app = make_app(5)
    async with app.run_test(size=(width, 20)) as pilot:
        await until(pilot, lambda: "5/5 shown" in status_line(app), what="the rows")
        for title in ("Sev", "Node", "Message"):
            assert title in header(app)
        row = screen_text(app).splitlines()[app.main.table.region.y + 3]
        # navigation.planner.costmap: its end, which tells it from navigation.planner, is kept
        assert "WARN" in row and (".planner.costmap " in row or " n.p.costmap " in row) and "planner failed" in row


async def test_command_palette_offers_the_actions():
    app = make_app(5)
    async with app.run_test(size=(100, 30)) as pilot:
        titles = [command.palette_title for command in app.commands.palette()]
        for title in ("Pause / resume", "Follow tail", "Clear", "Details", "Columns"):
            assert title in titles
        await pilot.press("ctrl+p")
        await type_text(pilot, "pause")
        await until(pilot, lambda: "Pause / resume" in screen_text(app), what="the palette offering Pause")
        await pilot.press("enter")
        await until(pilot, lambda: "PAUSED" in status_line(app), what="PAUSED")


async def test_a_change_of_focus_redraws_only_the_cursor_row():
    """Only the cursor's row may look different when the table has the focus; the other
    rows are not drawn again when the focus moves (the search line opening)."""
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        await until(pilot, lambda: cursor_number(app) == 100, what="the cursor on the last row")
        table = app.main.table
        other_y = table_rows(app)[99][0]
        other = style_at(app, 10, other_y)
        drawn = []
        draw = table.painter.row
        table.painter.row = lambda record, *args: drawn.append(record.seq + 1) or draw(record, *args)
        await pilot.press("f")
        await until(pilot, lambda: app.main.search_bar.is_open, what="the search line")
        # The cursor's row drawn in the blurred colours is the frame of the change of focus.
        await until(pilot, lambda: cursor_number(app) is None, what="the cursor's row drawn blurred")
        await frame_drawn(pilot)
        assert 100 in drawn, "the cursor's row was drawn again"
        assert style_at(app, 10, table_rows(app)[99][0]) == other
        assert set(drawn) <= {100}, f"rows drawn again: {sorted(set(drawn))}"
