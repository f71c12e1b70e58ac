"""Pilot tests of the table: follow, scroll, pause, resume, clear, details, help, columns."""

from __future__ import annotations

import io

import pytest
from rich.console import Console

from console_tui.ui.app import ConsoleApp
from console_tui.ui.commands import palette_commands
from console_tui.ui.screens.columns_dialog import ColumnsScreen
from console_tui.ui.screens.detail import DetailScreen
from console_tui.ui.screens.help import HelpScreen
from console_tui.ui.widgets.log_table import LogTable

from support.feed import records
from support.ui import make_app, screen_text


def line_text(table: LogTable, y: int) -> str:
    return table.render_line(y).text


def status_text(app: ConsoleApp) -> str:
    return rendered_text(app.status_bar.content)


def rendered_text(renderable) -> str:
    console = Console(width=200, record=True, file=io.StringIO())
    console.print(renderable)
    return console.export_text()


async def test_follows_the_tail_as_records_arrive():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        table = app.table
        await pilot.pause()
        assert table.following and table.cursor_row == 99
        assert "100" in line_text(table, table.size.height - 1)
        app.add_records(records(50, start=100))
        await pilot.pause()
        assert table.cursor_seq == 149
        assert table.scroll_y == table.max_scroll_y
        assert "FOLLOW" in status_text(app)


async def test_moving_up_stops_following_and_keeps_the_rows_in_place():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        table = app.table
        await pilot.press("up", "up", "up")
        assert not table.following
        cursor_seq, top = table.cursor_seq, table.scroll_y
        app.add_records(records(50, start=100))
        await pilot.pause()
        assert table.cursor_seq == cursor_seq and table.scroll_y == top
        assert "SCROLL" in status_text(app)
        await pilot.press("end")
        assert table.following and table.cursor_seq == 149


async def test_rows_arriving_below_the_screen_redraw_only_the_scrollbar():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        table = app.table
        await pilot.press("pageup")
        await pilot.pause()
        drawn = []
        draw = table.render_line
        table.render_line = lambda y: drawn.append(y) or draw(y)
        screen_before = [line_text(table, y) for y in range(table.size.height)]
        drawn.clear()
        app.add_records(records(500, start=100))
        await pilot.pause(0.3)  # the scrollbar follows within a tenth of a second
        assert drawn == []  # no row drawn again: the same rows, the same strips
        assert [line_text(table, y) for y in range(table.size.height)] == screen_before
        assert table.vertical_scrollbar.window_virtual_size == 601
        await pilot.press("end")
        assert table.following and table.cursor_seq == 599
        assert "600" in line_text(table, table.size.height - 1)


async def test_position_survives_eviction_at_the_bound():
    app = make_app(100, max_messages=120)
    async with app.run_test(size=(100, 24)) as pilot:
        table = app.table
        await pilot.press("pageup")
        cursor_seq = table.cursor_seq
        app.add_records(records(30, start=100))
        await pilot.pause()
        assert app.store.first_seq == 10
        assert table.cursor_seq == cursor_seq
        assert str(cursor_seq + 1) in line_text(table, table.cursor_row - int(table.scroll_y) + 1)


async def test_pause_freezes_the_view_counts_new_and_resume_catches_up():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        table = app.table
        await pilot.press("space")
        app.add_records(records(50, start=100))
        await pilot.pause()
        assert table.row_count == 100 and len(app.store) == 150
        assert table.new_while_paused == 50
        app.update_status()
        assert "PAUSED" in status_text(app) and "+50 new" in status_text(app)
        await pilot.press("space")
        await pilot.pause()
        assert table.row_count == 150 and table.cursor_seq == 149


async def test_clear_empties_the_view_and_numbering_goes_on():
    app = make_app(100)
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.press("c")
        assert len(app.store) == 0 and app.table.row_count == 0
        await pilot.pause()
        assert "0/0 shown" in screen_text(app) and not any(
            line.split()[:1] and line.split()[0].isdigit() for line in screen_text(app).splitlines()
        ), "no row left on the screen"
        app.add_records(records(3, start=500))
        await pilot.pause()
        assert app.table.row_count == 3 and app.table.cursor_seq == 102
        numbers = [
            line.split()[0] for line in screen_text(app).splitlines() if line.split()[:1] and line.split()[0].isdigit()
        ]
        assert numbers == ["101", "102", "103"] and "3/3 shown" in screen_text(app), "numbering goes on after a clear"


async def test_enter_opens_details_with_every_field_and_steps():
    app = make_app(20)
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.press("up", "up", "enter")
        screen = app.screen
        assert isinstance(screen, DetailScreen)
        record = screen.record
        assert record.seq == 17
        fields = rendered_text(screen.query_one("#fields").content)
        for value in (record.node, record.file, record.function, str(record.line), "1795000002.329000000"):
            assert value in fields
        await pilot.press("n")
        assert screen.record.seq == 18 and app.table.cursor_seq == 18
        await pilot.press("p", "p")
        assert screen.record.seq == 16
        await pilot.press("escape")
        assert not isinstance(app.screen, DetailScreen)


async def test_double_click_opens_details():
    app = make_app(10)
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.click(LogTable, offset=(20, 3), times=2)
        assert isinstance(app.screen, DetailScreen)
        assert app.screen.record.seq == 2


def words_on_screen(app: ConsoleApp) -> list[str]:
    """The screen's rows with each run of spaces (and the dialog's border) made one space."""
    return [" ".join(line.replace("█", " ").split()) for line in screen_text(app).splitlines()]


async def test_help_lists_keys_and_closes():
    app = make_app(5)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("question_mark")
        assert isinstance(app.screen, HelpScreen)
        await pilot.pause()
        first_page = words_on_screen(app)
        pages = [first_page]
        for _ in range(10):  # page down to the end, as a person reads it
            await pilot.press("pagedown")
            await pilot.pause()
            if words_on_screen(app) == pages[-1]:
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
        assert not isinstance(app.screen, HelpScreen)
        assert not any("space Pause" in line for line in words_on_screen(app)[:-1]), "only the footer names keys"


async def test_columns_can_be_hidden_and_shown():
    app = make_app(5)
    async with app.run_test(size=(160, 30)) as pilot:
        table = app.table
        assert "Function" in line_text(table, 0)
        await pilot.press("C")
        assert isinstance(app.screen, ColumnsScreen)
        await pilot.press("escape")
        table.set_column_shown("function", False)
        table.set_column_shown("source", True)
        await pilot.pause()
        header = line_text(table, 0)
        assert "Function" not in header and "Source" in header


@pytest.mark.parametrize("width", [60, 80, 120, 200])
async def test_narrow_terminals_keep_severity_node_and_message(width):
    app = make_app(5)
    async with app.run_test(size=(width, 20)) as pilot:
        await pilot.pause()
        header = line_text(app.table, 0)
        for title in ("Sev", "Node", "Message"):
            assert title in header


async def test_command_palette_offers_the_actions():
    app = make_app(5)
    async with app.run_test(size=(100, 30)) as pilot:
        titles = [command.title for command in palette_commands()]
        for title in ("Pause / resume", "Follow tail", "Clear", "Details", "Columns"):
            assert title in titles
        await pilot.press("ctrl+p")
        await pilot.press(*"pause")
        await pilot.press("enter")
        await pilot.pause()
        assert app.table.paused_end is not None
