"""Keys typed ahead, or pressed while the app is still starting, go where a person meant them.

Textual's ``Widget.focus`` queues the focus change behind the keys already waiting, so keys
typed right after ``/`` went to the table (issue 11, item 16: "the first / did nothing").
"""

from __future__ import annotations

import pytest

from console_tui.ui.app import ConsoleApp

from support.feed import records
from support.ui import line_with, make_app, screen_text, steady_cursors, type_ahead, until


async def test_text_typed_right_after_slash_lands_in_the_query_line():
    app = make_app(30)
    async with app.run_test(size=(100, 30)) as pilot:
        type_ahead(app, "/error")
        await until(pilot, lambda: app.main.query_bar.input.value == "error", what="the typed text")
        steady_cursors(app)
        await pilot.pause()
        _y, line = line_with(app, "error")
        assert line.strip().startswith("error")
        assert not app.main.rules_pane.is_open  # the r's did not reach the table
        assert "Open log files" not in screen_text(app)  # nor the o


@pytest.mark.first_frame
async def test_keys_typed_at_the_first_frame_wait_for_the_panes_mounted_after_it():
    """The first frame shows the table, the status line and the footer; the panes and lines
    hidden at start are mounted right after it. Keys typed at once wait for them: the text
    typed after ``/`` lands in the query line, and ``r`` typed after Escape opens the rules pane."""
    app = make_app(30)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press(*"/error")
        await until(pilot, lambda: _starts_a_line(app, "error"), what="the typed text in the query line")
        await pilot.press("escape", "r")
        await until(pilot, lambda: _starts_a_line(app, "Rules"), what="the rules pane")
        assert app.main.ready_for_keys


def _starts_a_line(app: ConsoleApp, text: str) -> bool:
    return any(line.lstrip(" │▏").startswith(text) for line in screen_text(app).splitlines())


class StartingApp(ConsoleApp):
    """Keys that arrived while the app was starting: queued before it mounted."""

    def on_mount(self) -> None:
        type_ahead(self, "/warn", keys=("up", "up"))
        super().on_mount()


@pytest.mark.first_frame
async def test_keys_pressed_while_the_app_starts_are_all_kept():
    app = StartingApp(utc=True)
    app.main.store.extend_records(records(50))
    async with app.run_test(size=(100, 30)) as pilot:
        await until(
            pilot, lambda: app.main.ready_for_keys and app.main.query_bar.input.value == "warn", what="the typed text"
        )
        await pilot.pause()
        assert app.main.table.cursor_seq == 47 and not app.main.table.following  # the two ups moved the table
        assert line_with(app, "warn")[1].strip().startswith("warn")
        assert "rule" in screen_text(app)  # the query line's verdict under it
