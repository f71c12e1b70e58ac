"""The command table: a command is one row in one file, and the key, the footer, the help screen,
the palette and the keymap all follow from it."""

from __future__ import annotations

from console_tui.ui.app import ConsoleApp
from console_tui.ui.command_table import Command

from support.feed import records
from support.ui import screen_text, type_text, until


class Freezer:
    """A controller only this test has: it needs nothing but the context, and declares one
    command (its row names a key no other command has)."""

    def __init__(self, context) -> None:
        self._table = context.table

    def freeze(self) -> None:
        self._table.set_paused(True)

    COMMANDS = (
        Command(
            "test.freeze",
            freeze,
            keys="ctrl+y",
            label="Freeze",
            footer=5,
            applies=lambda freezer: freezer._table.paused_end is None,
            title="Freeze the table",
            about="Stop the view, as a test says",
        ),
    )


class FreezingApp(ConsoleApp):
    """The console with the test's controller listed beside the others: nothing else changes."""

    CONTROLLERS = (*ConsoleApp.CONTROLLERS, Freezer)


def freezing_app() -> FreezingApp:
    from console_tui.model.store.log_store import LogStore

    store = LogStore()
    store.extend_records(records(40))
    return FreezingApp(store=store, utc=True)


async def test_a_row_in_a_new_controller_is_bound_in_the_footer_in_the_help_and_in_the_palette():
    app = freezing_app()
    async with app.run_test(size=(160, 40)) as pilot:
        footer = screen_text(app).splitlines()[-1]
        assert " ^y Freeze  space Pause " in footer, "the footer shows the key where its row says"
        await pilot.press("ctrl+y")
        await until(pilot, lambda: "PAUSED" in screen_text(app).splitlines()[-2], what="the key running its command")
        await until(
            pilot,
            lambda: "^y Freeze" not in screen_text(app).splitlines()[-1],
            what="the key gone, it no longer applies",
        )

        await pilot.press("question_mark")
        await until(pilot, lambda: "Change keys in" in screen_text(app), what="the help screen")
        for _ in range(60):  # the help screen scrolls: the Console group is below the table's keys
            if "test.freeze" in screen_text(app):
                break
            await pilot.press("down")
        help_line = next(line for line in screen_text(app).splitlines() if "test.freeze" in line)
        assert "^y" in help_line and "Freeze" in help_line

        await pilot.press("escape", "space")  # resumed: the command applies again
        await until(pilot, lambda: "FOLLOW" in screen_text(app).splitlines()[-2], what="resumed")
        await pilot.press("ctrl+p")
        await type_text(pilot, "freeze")
        await until(pilot, lambda: "Freeze the table" in screen_text(app), what="the palette's entry")
        assert "Stop the view, as a test says  (^y)" in screen_text(app), "the palette names its key"
        await pilot.press("enter")
        await until(pilot, lambda: "PAUSED" in screen_text(app).splitlines()[-2], what="the entry running the command")


async def test_a_keymap_moves_a_new_rows_key_by_its_id(own_config_folder):
    path = own_config_folder / "console-tui" / "keys.toml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text('test.freeze = "ctrl+b"\n')
    app = freezing_app()
    async with app.run_test(size=(160, 40)) as pilot:
        assert " ^b Freeze " in screen_text(app).splitlines()[-1]
        await pilot.press("ctrl+y")
        await pilot.press("ctrl+b")
        await until(pilot, lambda: "PAUSED" in screen_text(app).splitlines()[-2], what="the remapped key")
