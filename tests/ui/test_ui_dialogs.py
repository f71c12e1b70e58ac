"""The dialogs as a person reads them: columns, open, save, problems; each test reads the screen."""

from __future__ import annotations

import pytest

from support.ui import line_with, make_app, screen_text, type_ahead, until


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


def header(app) -> str:
    return screen_text(app).splitlines()[0]


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
        await pilot.press("down", "down", "down", "space")  # #, Time, Sev, Node: hides Node
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
        type_ahead(app, keys=("C", "down", "down", "down", "space", "enter"))
        await until(pilot, lambda: "Node" not in header(app), what="the Node column to go")
        assert "Columns shown" not in screen_text(app)
        assert not app.table.paused_end, "space reached the dialog, not the table"


async def test_columns_dialog_escape_changes_nothing():
    app = make_app(5)
    async with app.run_test(size=(120, 30)) as pilot:
        before = header(app)
        await pilot.press("C", "space", "escape")
        await until(pilot, lambda: "Columns shown" not in screen_text(app), what="the dialog to close")
        assert header(app) == before
