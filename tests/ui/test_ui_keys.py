"""Keys: a user's keys.toml remaps bindings by id, and every hint and the help follow it."""

from __future__ import annotations

from console_tui.ui.keys import load_keymap
from console_tui.ui.widgets.key_footer import KeyFooter

from support.feed import feed_logger_pane
from support.ui import frame_drawn, make_app, screen_text, toasts, until, until_shown


def write_keys(config, text: str):
    path = config / "console-tui" / "keys.toml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def test_the_keymap_file_flattens_tables_and_names_what_is_wrong(tmp_path):
    path = tmp_path / "keys.toml"
    path.write_text(
        'console.pause = "p"\n[loggers]\ndebug = ["D", "ctrl+d"]\ninfo = 3\n[nothing]\nhere = "z"\n',
    )
    loaded = load_keymap(path, lambda: ["console.pause", "loggers.debug", "loggers.info"])
    assert loaded.keys == {"console.pause": "p", "loggers.debug": "D,ctrl+d"}
    assert loaded.problems == (
        "keys.toml: loggers.info must be a key or a list of keys, not 3",
        "keys.toml: no key is named 'nothing.here'",
    )
    assert load_keymap(tmp_path / "absent.toml", list).keys == {}
    path.write_text("console.pause = \n")
    broken = load_keymap(path, lambda: ["console.pause"])
    assert broken.keys == {} and "not TOML" in broken.problems[0]


async def test_a_remapped_key_works_and_the_screen_names_it(own_config_folder):
    write_keys(own_config_folder, 'console.pause = "p"\nloggers.debug = "D"\nconsole.loggers = "ctrl+l"\n')
    app = make_app(5)
    async with app.run_test(size=(140, 30)) as pilot:
        await pilot.press("space")
        assert app.main.table.paused_end is None, "space no longer pauses"
        await pilot.press("p")
        assert app.main.table.paused_end is not None
        assert " p Resume " in screen_text(app).splitlines()[-1], "the footer names the new key (and what it does now)"
        await pilot.press("ctrl+l")
        feed_logger_pane(app.main.logger_pane)
        await pilot.pause()
        assert app.main.logger_pane.is_open
        assert "D/i/w/e/f level" in screen_text(app), "the pane's hint line follows the keymap"
        await pilot.press("escape", "question_mark")
        await pilot.pause()
        help_lines = screen_text(app).splitlines()
        assert any("p " in line and "Pause" in line and "console.pause" in line for line in help_lines)


async def test_a_bad_keymap_is_reported_and_the_default_keys_stay(own_config_folder):
    write_keys(own_config_folder, 'console.pause = "p"\nconsole.nothing = "n"\n')
    app = make_app(5)
    async with app.run_test(size=(120, 30), notifications=True) as pilot:
        await until(pilot, lambda: toasts(app, "warning"), what="the warning")
        warnings = toasts(app, "warning")
        assert "no key is named 'console.nothing'" in warnings[0]
        await pilot.press("p")
        await until(pilot, lambda: "PAUSED" in screen_text(app).splitlines()[-2], what="the good entries applying")


async def test_palette_entries_have_distinct_names_and_show_their_keys():
    app = make_app(5)
    titles = [command.palette_title for command in app.commands.palette()]
    assert len(titles) == len(set(titles))
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.press("ctrl+p", *"pause")
        await until_shown(pilot, "(space)")
        assert "(space)" in screen_text(app)
        system = [command.title for command in app.get_system_commands(app.screen)]
        assert "Keys" not in system, "Textual's key panel gives way to the help screen"


async def test_the_footer_draws_its_keys_again_only_when_they_change_and_asks_no_layout():
    """Textual's footer mounted its ~30 keys again on every signal, twice per change of
    focus, and laid out the screen after: the search line's opening and closing were the
    longest pauses of a search. The footer is one line now, drawn again when its keys
    change, and shows the same keys after as before."""
    app = make_app(50)
    async with app.run_test(size=(140, 30)) as pilot:
        footer = app.query_one(KeyFooter)
        await until(pilot, lambda: "Pause" in screen_text(app).splitlines()[-1], what="the footer's keys")
        keys_before = screen_text(app).splitlines()[-1]
        assert keys_before.startswith(" end Follow tail  ⏎ Details  space Pause"), keys_before
        assert keys_before.rstrip().endswith("▏^p palette"), keys_before
        layouts = []
        refresh = footer.refresh
        footer.refresh = lambda *a, layout=False, **k: layouts.append(layout) or refresh(*a, layout=layout, **k)
        before = footer.changes
        await pilot.press("f")
        await until(pilot, lambda: app.main.search_bar.is_open, what="the search line")
        await until(pilot, lambda: "f1 Help" in screen_text(app).splitlines()[-1], what="the search line's keys")
        await pilot.press("escape")
        await until(pilot, lambda: app.focused is app.main.table, what="the table focused again")
        # The table's keys back in the footer: the frame after the close's changes.
        await until(pilot, lambda: screen_text(app).splitlines()[-1] == keys_before, what="the table's keys again")
        await frame_drawn(pilot)
        assert footer.changes - before <= 2, f"{footer.changes - before} changes for open and close"
        assert True not in layouts, "the footer asked for a layout"
        assert screen_text(app).splitlines()[-1] == keys_before
        await pilot.press("space")  # pause: the footer's Pause becomes Resume
        await until(pilot, lambda: "Resume" in screen_text(app).splitlines()[-1], what="Resume in the footer")


async def test_a_click_on_a_key_in_the_footer_presses_it():
    app = make_app(50)
    async with app.run_test(size=(140, 30)) as pilot:
        await until(pilot, lambda: "Pause" in screen_text(app).splitlines()[-1], what="the footer's keys")
        bottom = len(screen_text(app).splitlines()) - 1
        await pilot.click(offset=(screen_text(app).splitlines()[-1].index("Pause"), bottom))
        await until(pilot, lambda: "PAUSED" in screen_text(app), what="paused by the click")
        await until(pilot, lambda: "Resume" in screen_text(app).splitlines()[-1], what="Resume in the footer")
        await pilot.click(offset=(screen_text(app).splitlines()[-1].index("space"), bottom))
        await until(pilot, lambda: "FOLLOW" in screen_text(app), what="resumed by the click")


async def test_a_key_that_stops_applying_leaves_the_footer_whoever_drew_it_last():
    """The footer drawn again by Textual (a focus move) while a load ran showed Cancel load; when
    the load ended, the console's check saw no change from what it had drawn itself and left
    the key there."""
    from console_tui.model.store.record_batch import RecordColumns

    from support.feed import records

    app = make_app(5)
    async with app.run_test(size=(160, 30)) as pilot:
        app.main.file_queue.put(RecordColumns.from_records(records(10, start=5)))  # a load's last records
        app.main.refresh_bindings()  # as Textual does when the focus moves
        await until(pilot, lambda: len(app.main.store) == 15, what="the load's records taken in")
        await until(pilot, lambda: "Cancel load" not in screen_text(app).splitlines()[-1], what="the key gone")
        assert " q Quit " in screen_text(app).splitlines()[-1]
