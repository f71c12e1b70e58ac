"""A change of focus redraws the widgets it changes, not the whole screen (``textual_fixes``):
closing the search line (the focus back to the table) was a frame of every line on screen."""

from __future__ import annotations

from textual.app import App, ComposeResult
from textual.widgets import Input, Static

from console_tui.ui import textual_fixes

from support.ui import screen_text


class _TwoInputs(App[None]):
    def compose(self) -> ComposeResult:
        yield Static("a line the focus does not touch", id="still")
        yield Input(value="first", id="one")
        yield Input(value="second", id="two")


async def test_moving_the_focus_redraws_only_the_lines_of_the_widgets_it_moves_between():
    textual_fixes.apply()
    app = _TwoInputs()
    async with app.run_test(size=(60, 10)) as pilot:
        app.query_one("#one", Input).focus()
        await pilot.pause()
        lines: list[int] = []  # the terminal lines each frame writes
        display = app._display

        def recording(screen, update) -> None:
            spans = getattr(update, "spans", None)  # a partial update: (line, start, end)
            lines.extend(range(app.size.height) if spans is None else [line for line, _, _ in spans])
            display(screen, update)

        app._display = recording  # type: ignore[method-assign]
        app.query_one("#two", Input).focus()
        await pilot.pause()
        await pilot.pause()
        assert app.focused is app.query_one("#two", Input)
        assert lines, "no frame was drawn for the change of focus"
        assert 0 not in lines, "the line the focus does not touch was written again"
        shown = screen_text(app)
    assert "a line the focus does not touch" in shown and "second" in shown
