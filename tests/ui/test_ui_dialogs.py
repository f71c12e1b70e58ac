"""The dialogs as a person reads them: columns, open, save, problems; each test reads the screen."""

from __future__ import annotations

import pytest

from support.ui import line_with, make_app, screen_text, type_ahead, type_text, until


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


def header(app) -> str:
    return screen_text(app).splitlines()[app.main.table.region.y]


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_columns_dialog_enter_applies_the_chosen_set_and_closes(size):
    app = make_app(5)
    async with app.run_test(size=size) as pilot:
        await pilot.press("C")
        await pilot.pause()
        text = screen_text(app)
        assert "Columns shown" in text
        assert "space shows or hides · ⏎ applies · esc cancels" in text  # the whole hint, not cut
        for title in ("# (number)", "Time", "Sev", "Node", "Message", "File", "Function", "Line", "Source"):
            line_with(app, title)
        await pilot.press("down", "down", "down", "down", "space")  # #, Time, Sev, Robot, Node: hides Node
        await pilot.press(*["down"] * 4, "space")  # File, Function, Line, Source (Message is skipped): shows it
        await pilot.pause()
        await pilot.press("enter")
        await until(pilot, lambda: "Columns shown" not in screen_text(app), what="the dialog to close")
        top = header(app)
        assert "Node" not in top and "Source" in top
        assert "Sev" in top and "Message" in top


async def test_columns_dialog_takes_keys_typed_all_at_once():
    app = make_app(5)
    async with app.run_test(size=(120, 30)) as pilot:
        type_ahead(app, keys=("C", "down", "down", "down", "down", "space", "enter"))
        await until(pilot, lambda: "Node" not in header(app), what="the Node column to go")
        assert "Columns shown" not in screen_text(app)
        assert not app.main.table.paused_end, "space reached the dialog, not the table"


async def test_columns_dialog_escape_changes_nothing():
    app = make_app(5)
    async with app.run_test(size=(120, 30)) as pilot:
        before = header(app)
        await pilot.press("C", "space", "escape")
        await until(pilot, lambda: "Columns shown" not in screen_text(app), what="the dialog to close")
        assert header(app) == before


def input_value(app) -> str:
    from textual.widgets import Input

    return app.screen.query_one(Input).value


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_open_dialog_tab_takes_the_completion_and_nothing_is_cut(tmp_path, monkeypatch, size):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "recordings").mkdir()
    (tmp_path / "recordings" / "run1.mcap").write_text("")
    app = make_app(5)
    async with app.run_test(size=size) as pilot:
        await pilot.press("o")
        await type_text(pilot, "rec")
        await until(pilot, lambda: "recordings/" in screen_text(app), what="the completion shown")
        text = screen_text(app)
        assert "Open log files, recordings or folders" in text
        assert "spaces separate files · tab completes · ⏎ opens · esc cancels" in text
        await pilot.press("tab")
        assert input_value(app) == "recordings/"
        await until(pilot, lambda: "recordings/run1.mcap" in screen_text(app), what="the next completion")
        await pilot.press("tab")
        assert input_value(app) == "recordings/run1.mcap"
        await pilot.press("tab")  # nothing more to complete: on to the next field, the text stays
        assert input_value(app) == "recordings/run1.mcap"


async def test_open_dialog_says_what_is_missing_as_typed(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    app = make_app(5)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("o")
        await type_text(pilot, "no[such]file")
        await pilot.press("enter")
        await until(pilot, lambda: "No such file" in screen_text(app), what="the problem")
        assert "No such file: no[such]file" in screen_text(app)  # brackets are no markup


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_save_dialog_shows_every_part_and_its_keys(size):
    app = make_app(5)
    async with app.run_test(size=size) as pilot:
        await pilot.press("s")
        await until(pilot, lambda: "Save messages to" in screen_text(app), what="the save dialog")
        text = screen_text(app)
        assert "Save messages to (the extension picks the format)" in text
        for title in ("rqt_console (ROS 2) .csv", "rqt_console (ROS 1) .csv", "JSON Lines, every field .jsonl"):
            assert title in text
        assert "Only the rows shown (after rules)" in text
        assert "tab completes · ⏎ saves · esc cancels" in text
