"""Hostile messages: escapes, controls, huge and wide text stay inert and intact."""

from __future__ import annotations

import re

import pytest

from console_tui.model.inert_text import multi_line
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.ui.app import ConsoleApp
from console_tui.ui.screens.detail import DetailScreen

from support.ui import foreign_controls, table_rows, terminal_output, until, widget_lines

HOSTILE = {
    "ansi": "red \x1b[31mRED\x1b[0m then \x1b[2J\x1b[H cleared \x1b[?1049h alt screen",
    "osc": "title \x1b]0;pwned\x07 link \x1b]8;;http://example.invalid\x1b\\text\x1b]8;;\x1b\\ clipboard \x1b]52;c;aGk=\x07",
    "controls": "nul\x00 bell\x07 backspace\x08 cr\r vt\x0b ff\x0c del\x7f csi8bit\x9b31m",
    "megabyte": "0123456789abcdef" * 65_536,
    "ten_thousand_lines": "\n".join(f"line {i}" for i in range(10_000)),
    "wide": "漢字テスト 🚀🤖👩‍👩‍👧 emoji مرحبا بالعالم עברית",
    "bidi": "safe \u202eevil reversed\u202c \u2066isolate\u2069 \u200fmark",
    "markup": "[bold red]not markup[/] [link=http://x]x[/link] :smile:",
}
CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069\u200e\u200f]")


def hostile_app() -> ConsoleApp:
    store = LogStore()
    store.extend_records(
        LogRecord(
            stamp_ns=1_795_000_000_000_000_000 + i,
            level=20 + 10 * (i % 3),
            node=f"hostile.{name}",
            msg=text,
            file=f"/tmp/\x1b[31m{name}.py",
            function="attack\x00",
            line=i,
        )
        for i, (name, text) in enumerate(HOSTILE.items())
    )
    return ConsoleApp(store=store, utc=True)


async def test_table_rows_render_inert():
    app = hostile_app()
    async with app.run_test(size=(160, 30)) as pilot:
        await until(pilot, lambda: len(table_rows(app)) == len(HOSTILE), what="every row on the screen")
        table = app.main.table
        lines = widget_lines(app, table)  # the header, then a row a record
        for y, line in enumerate(lines):
            assert not CONTROL.search(line), f"line {y} leaks {line!r}"
        assert foreign_controls(terminal_output(app)) == []
        text = "".join(lines[1 : len(HOSTILE) + 1])
        assert "[bold red]not markup[/]" in text
        assert "漢字テスト" in text
        # the app is still alive and answering keys
        await pilot.press("up")
        assert table.cursor_row == len(HOSTILE) - 2


@pytest.mark.parametrize("name", list(HOSTILE))
async def test_detail_view_shows_every_message_intact(name):
    app = hostile_app()
    index = list(HOSTILE).index(name)
    async with app.run_test(size=(120, 40)) as pilot:
        await until(pilot, lambda: len(table_rows(app)) == len(HOSTILE), what="every row on the screen")
        await pilot.press("home", *["down"] * index, "enter")  # the record's row, its details
        await until(pilot, lambda: isinstance(app.screen, DetailScreen), what="the detail view")
        screen = app.screen
        assert isinstance(screen, DetailScreen)
        area = screen.query_one("#message")
        assert area.text == multi_line(HOSTILE[name])
        flat = area.text.replace("\n", "").replace("\t", "")
        assert CONTROL.sub("", flat) == flat
        if name == "ten_thousand_lines":
            assert area.document.line_count == 10_000
        if name == "megabyte":
            assert len(area.text) == 1_048_576
        await pilot.press("end", "escape")
        assert not isinstance(app.screen, DetailScreen)


async def test_screenshot_of_hostile_rows_has_no_raw_escapes():
    app = hostile_app()
    async with app.run_test(size=(160, 30)) as pilot:
        await pilot.pause()
        svg = app.export_screenshot()
        assert "\x1b" not in svg and "\x00" not in svg
