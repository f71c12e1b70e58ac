"""Every one-line text box shows what is typed into it, with its cursor, on the screen.

The keys are typed one at a time and the terminal's rows are read back: a box whose border
or height leaves no row for its text (the focused Input's tall border winning over a
``border: none``, as happened to the query line) fails here.
"""

from __future__ import annotations

from functools import partial

import pytest

from console_tui.ui.screens.temporary_level import TemporaryLevelScreen

from support import ui
from support.feed import feed_logger_pane
from support.ui import cursor_after, frame_drawn, line_with, screen_text, steady_cursors, type_text, until, until_shown

make_app = partial(ui.make_app, count=300)


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    """Query history and rule sets of these tests stay in a folder of their own."""
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


async def on_screen(pilot, text: str) -> None:
    """Wait until ``text`` is painted (a key's effect can take a moment on a busy machine)."""
    await until(pilot, lambda: text in screen_text(pilot.app), what=repr(text))


async def type_into(pilot, text: str, *, clear: bool = False) -> None:
    """Type ``text`` into the focused box, key by key (after emptying it with ctrl+u)."""
    steady_cursors(pilot.app)
    if clear:
        await pilot.press("end", "ctrl+u")
    await type_text(pilot, text)
    await pilot.pause()


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_query_line_shows_the_typed_text_its_cursor_and_the_error_caret(size):
    app = make_app()
    async with app.run_test(size=size) as pilot:
        await pilot.press("slash")
        await on_screen(pilot, "closes")
        await type_into(pilot, "level>=warn node:nav*")
        y, line = line_with(app, "level>=warn node:nav*")
        rows = screen_text(app).splitlines()
        assert rows[y + 1].strip().startswith("1 rule · ") and "applies" in rows[y + 1], rows[y + 1]
        assert "FOLLOW" in rows[y + 2], "the query line sits right above the status line"
        assert cursor_after(app, "level>=warn node:nav*"), "the cursor shows after the text"

        await type_into(pilot, " /time(out")
        y, line = line_with(app, "level>=warn node:nav* /time(out")
        # Under the line: the query again with a caret under the problem, then the reason.
        caret_row = next(row for row in screen_text(app).splitlines()[y + 1 :] if "^" in row)
        column = caret_row.index("^")
        assert line[column] == "/", "the caret points at the regex that is not closed"
        assert "unterminated regular expression" in caret_row
        assert "the rules in force stay" in screen_text(app)

        await type_into(pilot, "/")  # closed now, but the regex itself is wrong: the caret moves
        assert "missing )" in screen_text(app)
        await pilot.press("backspace", "backspace", "backspace", "backspace", "backspace")
        await type_into(pilot, "/")
        assert line_with(app, "level>=warn node:nav* /time/")[1]
        assert "1 rule ·" in screen_text(app) and "the rules in force stay" not in screen_text(app)


async def test_open_dialog_shows_the_typed_paths(tmp_path):
    app = make_app()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("o")
        await on_screen(pilot, "Open log files")
        await type_into(pilot, "run1.bag saved.csv")
        assert cursor_after(app, "run1.bag saved.csv")


async def test_save_dialog_shows_the_typed_path():
    app = make_app()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("s")
        await on_screen(pilot, "Save messages to")
        await type_into(pilot, "/tmp/typed-here.jsonl", clear=True)
        y, _ = line_with(app, "/tmp/typed-here.jsonl")
        assert "Save messages to" in "".join(screen_text(app).splitlines()[y - 3 : y])
        assert cursor_after(app, "/tmp/typed-here.jsonl")


@pytest.mark.parametrize("key, title", [("S", "Save the rules to"), ("O", "Open rules from")])
async def test_rule_set_path_dialogs_show_the_typed_path(key, title):
    app = make_app()
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("r")
        await on_screen(pilot, "O open")
        await pilot.press(key)
        await on_screen(pilot, title)
        await type_into(pilot, "my-rules.toml", clear=True)
        line_with(app, "my-rules.toml")
        assert cursor_after(app, "my-rules.toml")


@pytest.mark.parametrize(
    "field, text",
    [
        ("message-text", "timed out"),
        ("node-names", "nav*, /ns/talker"),
        ("location-file", "planner.cpp"),
        ("location-function", "on_timer"),
        ("location-line", "120"),
        ("time-from", "12:30"),
        ("time-to", "2024-05-01T08:00"),
    ],
)
async def test_rule_editor_boxes_show_the_typed_text(field, text):
    app = make_app()
    async with app.run_test(size=(120, 50)) as pilot:
        await pilot.press("r")
        await on_screen(pilot, "O open")
        await pilot.press("a")
        await on_screen(pilot, "New rule")
        # The kind list: the last kind, custom, shows every field.
        await pilot.press("enter")
        await on_screen(pilot, "Custom: all of the fields below")
        await pilot.press("end", "enter")
        await until(pilot, lambda: str(app.screen.query_one("#kind").value) == "custom", what="the custom kind")
        for _ in range(30):  # Tab to the box, as a person does
            if app.focused is not None and app.focused.id == field:
                break
            await pilot.press("tab")
        assert app.focused.id == field
        await type_into(pilot, text)
        line_with(app, text)
        assert cursor_after(app, text)


async def test_logger_pane_add_logger_box_shows_the_typed_name():
    app = make_app(clock=lambda: 100.0)
    async with app.run_test(size=(140, 30)) as pilot:
        await pilot.press("l")
        feed_logger_pane(app.main.logger_pane)
        await pilot.pause()
        await pilot.press("a")
        await until(pilot, lambda: app.main.logger_pane.name_input.has_focus, what="the logger name box")
        await type_into(pilot, "navigation.planner.extra")
        line_with(app, "navigation.planner.extra")
        assert cursor_after(app, "navigation.planner.extra")


async def test_temporary_level_seconds_box_shows_the_typed_number():
    app = make_app()
    async with app.run_test(size=(100, 30)) as pilot:
        app.push_screen(TemporaryLevelScreen("/n", "n", 30))
        await until(pilot, lambda: isinstance(app.screen, TemporaryLevelScreen))
        await on_screen(pilot, "For how many seconds")
        await until(pilot, lambda: app.focused is not None and app.focused.id == "temporary-seconds")
        await type_into(pilot, "45.25", clear=True)
        y, _ = line_with(app, "45.25")
        assert "seconds" in "\n".join(screen_text(app).splitlines()[y - 3 : y])
        assert cursor_after(app, "45.25")
        await pilot.press("backspace", "backspace")
        await type_into(pilot, "0", clear=True)
        await pilot.press("enter")
        assert "Seconds must be a number above 0, not '0'" in screen_text(app)


async def test_typing_in_the_search_line_shows_the_text_without_laying_out_the_screen():
    """Textual's ``Input`` laid out the whole screen on every key (its virtual size is
    its text's width); the search and query lines' inputs do not."""
    app = make_app()
    async with app.run_test(size=(100, 24)) as pilot:
        await pilot.press("f")
        await until(pilot, lambda: app.main.search_bar.is_open, what="the search line")
        await until_shown(pilot, "esc cancels")  # the line laid out and drawn
        await frame_drawn(pilot)
        screen = app.screen
        layouts = []
        screen.screen_layout_refresh_signal.subscribe(app, layouts.append, immediate=True)
        await pilot.press(*"divisible")
        await until(pilot, lambda: "divisible" in screen_text(app), what="the typed text")
        await frame_drawn(pilot)
        assert layouts == [], f"{len(layouts)} layouts of the screen while typing"
        await pilot.press("escape")  # a layout, to show the count is the screen's own
        await until(pilot, lambda: layouts, what="the layout closing the search line asks")
