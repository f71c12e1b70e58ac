"""Finding your way, as a person does it, reading the screen: search with its marks and
"match X of Y", n / N across 100k messages, next error from the top, level keys and node
solo / mute with the status line's words, every time format, marks, and the source file
opened in the editor."""

from __future__ import annotations

import json
import stat
import sys

import pytest
from textual.binding import Binding

from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.ui.app import ConsoleApp

from support.feed import BASE_NS, records
from support.ui import line_with, make_app, screen_text, steady_cursors, style_at, type_text, until

NEEDLES = (100, 50_000, 90_000)


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


def status_line(app: ConsoleApp) -> str:
    """The status line as the screen shows it (it starts with the table's state)."""
    lines = screen_text(app).splitlines()
    found = [line for line in lines if line.split()[:1] in (["FOLLOW"], ["SCROLL"], ["PAUSED"])]
    assert found, "no status line on the screen:\n" + "\n".join(lines)
    return found[-1]


def number_of(line: str) -> str:
    """The row number a table line starts with (after the gutter's mark, if any)."""
    words = line.split()
    return words[1] if words[0] in ("»", "●") else words[0]


def cursor_line(app: ConsoleApp) -> str:
    """The table row the screen paints as the cursor's (found by its colour)."""
    table = app.main.table
    cursor = table.get_component_rich_style("log-table--cursor", partial=True).bgcolor
    lines = screen_text(app).splitlines()
    region = table.region
    for y in range(region.y + 1, region.y + region.height):
        if style_at(app, region.x + 3, y).bgcolor == cursor:
            return lines[y]
    raise AssertionError("no row is painted as the cursor:\n" + "\n".join(lines))


def big_app(count: int = 100_000, *, needles=NEEDLES, error_at: int | None = None, **options) -> ConsoleApp:
    """``count`` records; the messages at ``needles`` hold "needle"; with ``error_at`` every
    record is INFO but that one, an ERROR."""
    made = records(count)
    for seq in needles:
        made[seq].msg = f"found the needle {seq}"
    if error_at is not None:
        for rec in made:
            rec.level = 20
        made[error_at].level = 40
        made[error_at].msg = "the only error"
    store = LogStore()
    store.extend_records(made)
    return ConsoleApp(store=store, utc=True, **options)


async def search_for(pilot, app: ConsoleApp, text: str) -> None:
    await pilot.press("f")
    steady_cursors(app)
    await type_text(pilot, text)
    await pilot.press("enter")
    await until(
        pilot,
        lambda: "match" in app.main.searching.search_status() and "searching" not in app.main.searching.search_status(),
    )


# -- search -------------------------------------------------------------------------------------


async def test_search_marks_every_match_and_counts_them():
    app = make_app(200)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.pause()
        await search_for(pilot, app, "battery")
        # Following the tail, the search goes to the newest match: 20 batteries in 200 rows.
        assert "match 20 of 20 'battery'" in status_line(app)
        assert "battery 24.3 V" in cursor_line(app)
        lines = [line for line in screen_text(app).splitlines() if "battery 24.3 V" in line]
        assert lines and all(line.startswith("»") for line in lines)
        others = [line for line in screen_text(app).splitlines() if "Counted to" in line]
        assert others and not any(line.startswith("»") for line in others)
        await pilot.press("N")
        await pilot.pause()
        assert "match 19 of 20 'battery'" in status_line(app)
        await pilot.press("up")
        await pilot.pause()
        assert "20 matches 'battery'" in status_line(app)
        # The matched text is painted apart from the rest of the message.
        y, line = line_with(app, "battery 24.3 V")
        x = line.index("battery 24.3 V")
        assert style_at(app, x, y) != style_at(app, x + len("battery") + 1, y)
        # Esc in the table clears the search: no marks, no counter.
        await pilot.press("escape")
        await pilot.pause()
        assert "battery" not in status_line(app)
        assert not any(line.startswith("»") for line in screen_text(app).splitlines())


async def test_search_line_says_a_bad_regex_and_esc_goes_back():
    app = make_app(200)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("home")
        await pilot.pause()
        await pilot.press("f")
        await type_text(pilot, "/time(out/")
        await pilot.pause()
        line_with(app, "missing ), unterminated subpattern")
        await pilot.press("ctrl+u")
        await type_text(pilot, "/DIVISIBLE/i")
        await until(pilot, lambda: "divisible" in cursor_line(app))
        await pilot.press("escape")
        await pilot.pause()
        assert number_of(cursor_line(app)) == "1"  # back on the first row
        assert "DIVISIBLE" not in status_line(app)


async def test_next_and_previous_match_across_100k_messages():
    app = big_app()
    async with app.run_test(size=(100, 30), notifications=True) as pilot:
        await pilot.press("home")
        await pilot.pause()
        await search_for(pilot, app, "needle")
        assert "found the needle 100" in cursor_line(app)
        assert "match 1 of 3 'needle'" in status_line(app)
        await pilot.press("n")
        await until(pilot, lambda: "needle 50000" in cursor_line(app))
        assert number_of(cursor_line(app)) == "50001"
        assert "match 2 of 3 'needle'" in status_line(app)
        await pilot.press("n")
        await until(pilot, lambda: "needle 90000" in cursor_line(app))
        assert "match 3 of 3" in status_line(app)
        await pilot.press("n")
        await until(pilot, lambda: "No match below" in screen_text(app))
        assert "needle 90000" in cursor_line(app)
        await pilot.press("N", "N")
        await until(pilot, lambda: "needle 100" in cursor_line(app))
        assert "match 1 of 3" in status_line(app)


async def test_search_counts_only_rows_the_rules_show():
    app = big_app(needles=(100, 101, 102))
    async with app.run_test(size=(100, 30)) as pilot:
        await search_for(pilot, app, "needle")
        assert "match 3 of 3" in status_line(app)
        await pilot.press("slash")
        await type_text(pilot, "-node:count_and_log")  # the needle at 100 was logged by count_and_log
        await pilot.press("enter")
        await until(pilot, lambda: "of 2" in status_line(app) or "2 matches" in status_line(app))


# -- jumps ---------------------------------------------------------------------------------------


async def test_next_error_from_the_top_of_a_100k_history():
    app = big_app(needles=(), error_at=98_765)
    async with app.run_test(size=(100, 30), notifications=True) as pilot:
        await pilot.press("home")
        await pilot.pause()
        assert cursor_line(app).split()[0] == "1"
        await pilot.press("e")
        await until(pilot, lambda: "the only error" in cursor_line(app))
        assert cursor_line(app).split()[:3] == ["98766", "14:52:10.805", "ERROR"]
        assert "SCROLL" in status_line(app)
        await pilot.press("e")
        await until(pilot, lambda: "No ERROR or worse below" in screen_text(app))
        await pilot.press("end", "E")
        await until(pilot, lambda: "the only error" in cursor_line(app))
        await pilot.press("w")  # WARN or worse: the error is the only one
        await until(pilot, lambda: "No WARN or worse below" in screen_text(app))


async def test_marks_in_the_gutter_listed_and_jumped_between():
    app = make_app(300)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("home", "down", "down", "m")  # row 3
        for _ in range(10):
            await pilot.press("down")
        await pilot.press("m")  # row 13
        await pilot.pause()
        marked = [line.split()[1] for line in screen_text(app).splitlines() if line.startswith("●")]
        assert marked == ["3", "13"]
        await pilot.press("home", "u")
        await pilot.pause()
        assert cursor_line(app).split()[1] == "3"
        await pilot.press("u")
        await pilot.pause()
        assert cursor_line(app).split()[1] == "13"
        await pilot.press("U")
        await pilot.pause()
        assert cursor_line(app).split()[1] == "3"
        await pilot.press("end", "M")
        await pilot.pause()
        line_with(app, "2 marks")
        line_with(app, "      3 11:06:40.274 WARN  navigation.planner.costmap planner failed")  # row 3, in the list
        await pilot.press("down", "enter")
        await pilot.pause()
        assert cursor_line(app).split()[1] == "13"
        await pilot.press("m", "home")  # unmark it
        await pilot.pause()
        assert [line.split()[1] for line in screen_text(app).splitlines() if line.startswith("●")] == ["3"]


# -- levels and nodes ----------------------------------------------------------------------------


async def test_level_keys_hide_levels_and_say_so_in_the_status_line():
    app = make_app(300)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        await pilot.press("2")
        await pilot.pause()
        assert "hiding INFO" in status_line(app)
        assert "150/300 shown" in status_line(app)
        await pilot.press("2", "1")
        await pilot.pause()
        assert "level≥INFO" in status_line(app)
        assert "270/300 shown" in status_line(app)
        await pilot.press("greater_than_sign")
        await pilot.pause()
        assert "level≥WARN" in status_line(app)
        rows = screen_text(app).splitlines()[app.main.table.region.y + 1 : -3]  # below the timeline and the header
        severities = {line.split()[2] for line in rows if line.split()[:1] != []}
        assert severities <= {"WARN", "ERROR", "FATAL"}, severities
        await pilot.press("4")  # hide ERROR too
        await pilot.pause()
        assert "level≥WARN, hiding ERROR" in status_line(app)
        await pilot.press("r")  # the toggles are a rule in the rules pane
        await pilot.pause()
        line_with(app, "hide severity DEBUG, INFO, ERROR  (level")
        await pilot.press("escape", "r", "0")
        await pilot.pause()
        assert "hiding" not in status_line(app) and "300/300 shown" in status_line(app)


async def test_node_panel_solo_and_mute():
    app = make_app(300)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        await pilot.press("ctrl+n")
        await pilot.pause()
        line_with(app, "Nodes: 5")
        assert line_with(app, "power.battery_monitor")[1].split("▏")[1].split()[1:] == [
            "30",
            "0",
            "0",
            "0",
            "30",
            "1.5",
        ]
        # The filter box, then solo the one node left.
        await pilot.press("slash")
        await type_text(pilot, "lidar")
        await pilot.press("enter")
        await pilot.pause()
        line_with(app, "1 shown")
        await pilot.press("s")
        await pilot.pause()
        assert "solo sensors.lidar_driver" in status_line(app)
        assert "60/300 shown" in status_line(app)
        line_with(app, "S sensors.lidar_driver")
        await pilot.press("s")  # again: out of the solo
        await pilot.pause()
        assert "solo" not in status_line(app) and "300/300 shown" in status_line(app)
        await pilot.press("m")
        await pilot.pause()
        assert "muted sensors.lidar_driver" in status_line(app)
        assert "240/300 shown" in status_line(app)
        await pilot.press("x")
        await pilot.pause()
        assert "muted" not in status_line(app)
        # The logger levels pane takes the panel's place.
        await pilot.press("escape", "l")
        await pilot.pause()
        assert "Nodes: 5" not in screen_text(app)


async def test_node_panel_with_80_nodes_filters_and_sorts():
    store = LogStore()
    store.extend_records(
        LogRecord(stamp_ns=BASE_NS + i, level=40 if i % 80 == 7 else 20, node=f"robot.part_{i % 80:02d}", msg="m")
        for i in range(8000)
    )
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.press("ctrl+n")
        await pilot.pause()
        line_with(app, "Nodes: 80")
        first = pane_lines(app, "robot.part_")[0]
        assert "robot.part_07" in first  # sorted by errors first
        await pilot.press("o")  # then by warnings, messages, rate, name
        await pilot.press("o", "o", "o")
        await pilot.pause()
        first = pane_lines(app, "robot.part_")[0]
        assert "robot.part_00" in first
        await pilot.press("slash")
        await type_text(pilot, "part_7")
        await pilot.pause()
        line_with(app, "Nodes: 80 · 10 shown")


async def test_node_panel_counts_what_came_while_closed_a_budget_at_a_time(monkeypatch):
    """Nothing is counted while the panel is closed; opened, it counts a budget's worth at a
    time and says so until done."""
    from console_tui.model.store.log_store import CHUNK_SIZE
    from console_tui.ui.widgets import node_pane

    monkeypatch.setattr(node_pane, "COUNT_BUDGET_S", 0.0)  # one chunk a refresh
    monkeypatch.setattr(node_pane, "CATCH_UP_S", 3600.0)  # the test calls the refreshes
    store = LogStore()
    store.extend_records(
        LogRecord(stamp_ns=BASE_NS + i, level=20, node="robot.arm" if i < CHUNK_SIZE else "robot.base", msg="m")
        for i in range(3 * CHUNK_SIZE)
    )
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        assert not app.main.node_stats.counted  # nobody asked yet
        await pilot.press("ctrl+n")
        await pilot.pause()
        line_with(app, "Nodes: 1 · counting…")
        assert pane_lines(app, "robot.")[0].split()[:3] == ["robot.arm", "0", str(CHUNK_SIZE)]
        pane = app.main.node_pane
        pane.update_counts()
        pane.update_counts()
        await pilot.pause()
        line_with(app, "Nodes: 2")
        assert "counting" not in screen_text(app)
        assert pane_lines(app, "robot.base")[0].split()[:3] == ["robot.base", "0", str(2 * CHUNK_SIZE)]


def pane_lines(app: ConsoleApp, text: str) -> list[str]:
    """Lines of the side pane (right of its border) holding ``text``."""
    return [
        line.split("▏", 1)[1] for line in screen_text(app).splitlines() if "▏" in line and text in line.split("▏", 1)[1]
    ]


# -- time formats --------------------------------------------------------------------------------


async def test_every_time_format_on_a_fixed_data_set():
    app = make_app(100)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.press("home", "down")  # row 2, 137 ms after the first
        await pilot.pause()

        def time_cell() -> str:
            line = cursor_line(app)
            return line[8 : line.index(" INFO ")].strip()

        expected = [
            ("Date and time UTC", "2026-11-18 11:06:40.137"),
            ("Stamp", "1795000000.137000000"),
            ("Since first", "+0.137"),
            ("Since row", "0.000"),
            ("Δ previous", "+0.137"),
            ("Time UTC", "11:06:40.137"),
        ]
        assert time_cell() == "11:06:40.137"
        line_with(app, "Time UTC")
        for title, cell in expected:
            await pilot.press("t")
            await pilot.pause()
            line_with(app, title)
            assert time_cell() == cell, title
        await pilot.press("t", "t", "t", "t")  # since the selected row: the rows around it count from it
        await pilot.pause()
        line_with(app, "Since row")
        assert "time: time since the selected row" in status_line(app)
        assert "      3 +0.137" in screen_text(app)
        assert "      1 -0.137" in screen_text(app)
        await pilot.press("t", "t", "ctrl+u")  # the wall clock, in local time
        await pilot.pause()
        line_with(app, " Time ")


async def test_sim_time_is_said():
    store = LogStore()
    store.extend_records(
        LogRecord(stamp_ns=12_500_000_000 + i * 10**8, level=20, node="sim", msg=f"tick {i}") for i in range(50)
    )
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.pause()
        assert "stamps look like sim time (near 0)" in status_line(app)
        await pilot.press("t", "t")
        await pilot.pause()
        line_with(app, "17.400000000")


# -- the source ----------------------------------------------------------------------------------


@pytest.fixture
def fake_editor(tmp_path, monkeypatch):
    """An editor that writes the arguments it was given to a file, and the file."""
    said = tmp_path / "editor-args.json"
    script = tmp_path / "fake-editor"
    script.write_text(
        f"#!{sys.executable}\nimport json, sys\nopen({str(said)!r}, 'w').write(json.dumps(sys.argv[1:]))\n"
    )
    script.chmod(script.stat().st_mode | stat.S_IEXEC)
    monkeypatch.setenv("VISUAL", f"{script} --wait")
    return said


async def test_the_source_opens_in_the_editor_at_its_line(tmp_path, fake_editor):
    source = tmp_path / "src" / "planner.cpp"
    source.parent.mkdir()
    source.write_text("int main() {}\n" * 50)
    store = LogStore()
    store.extend_records(
        [
            LogRecord(stamp_ns=BASE_NS, level=40, node="planner", msg="here", file=str(source), line=42),
            LogRecord(stamp_ns=BASE_NS, level=40, node="planner", msg="robot", file="/opt/robot/src/x.cpp", line=7),
        ]
    )
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(120, 30), notifications=True) as pilot:
        await pilot.press("home", "v")
        await until(pilot, fake_editor.exists, what="the editor")
        assert json.loads(fake_editor.read_text()) == ["--wait", "+42", str(source)]
        await pilot.press("down", "v")
        await until(pilot, lambda: "is not on this machine" in screen_text(app))
        line_with(app, "/opt/robot/src/x.cpp")


async def test_an_editor_that_is_not_installed_is_named_and_the_table_stays(tmp_path, monkeypatch):
    source = tmp_path / "planner.cpp"
    source.write_text("int main() {}\n")
    monkeypatch.delenv("VISUAL", raising=False)
    monkeypatch.setenv("EDITOR", "no-such-editor-nvim --clean")
    store = LogStore()
    store.append(LogRecord(stamp_ns=BASE_NS, level=40, node="planner", msg="here", file=str(source), line=3))
    app = ConsoleApp(store=store, utc=True)
    async with app.run_test(size=(120, 30), notifications=True) as pilot:
        await pilot.press("v")
        await until(pilot, lambda: "was not found" in screen_text(app), what="the editor not found")
        line_with(app, "no-such-editor-nvim ($EDITOR)")
        line_with(app, "here")  # the table is still there, and the keys still work
        await pilot.press("j")


def bare_name_store() -> LogStore:
    store = LogStore()
    store.append(
        LogRecord(stamp_ns=BASE_NS, level=20, node="/r1node", msg="tick", file="r1node.py", line=9, source="r1.log")
    )
    return store


async def test_a_bare_file_name_never_opens_from_the_working_directory(tmp_path, monkeypatch, fake_editor):
    elsewhere = tmp_path / "cwd"
    elsewhere.mkdir()
    (elsewhere / "r1node.py").write_text("# another file of the same name\n")
    monkeypatch.chdir(elsewhere)
    app = ConsoleApp(store=bare_name_store(), utc=True)
    async with app.run_test(size=(120, 30), notifications=True) as pilot:
        await pilot.press("v")
        await until(pilot, lambda: "names no folder" in screen_text(app), what="the bare name refused")
        line_with(app, "working directory is not searched")
    assert not fake_editor.exists()


async def test_a_bare_file_name_opens_under_the_run_folder(tmp_path, monkeypatch, fake_editor):
    run = tmp_path / "run"
    run.mkdir()
    (run / "r1node.py").write_text("print('hi')\n" * 20)
    (run / "r1.log").write_text("")
    elsewhere = tmp_path / "cwd"
    elsewhere.mkdir()
    (elsewhere / "r1node.py").write_text("# another file of the same name\n")
    monkeypatch.chdir(elsewhere)
    app = ConsoleApp(store=bare_name_store(), utc=True)
    app.main.files.opened_paths.append(str(run / "r1.log"))
    async with app.run_test(size=(120, 30), notifications=True) as pilot:
        await pilot.press("v")
        await until(pilot, fake_editor.exists, what="the editor")
    assert json.loads(fake_editor.read_text()) == ["--wait", "+9", str(run.resolve() / "r1node.py")]


# -- palette, help, keymap -----------------------------------------------------------------------


async def test_every_palette_entry_names_an_action_and_a_key_that_exist():
    app = make_app(5)
    async with app.run_test(size=(100, 30)):
        ids = {b.id for _title, group in app.binding_groups() for b in group if b.id}
        for command in app.commands.palette():
            assert command.action == f"command({command.id!r})" and command.id in app.commands, command.id
            assert not command.key_id or command.key_id in ids, command.key_id


async def test_a_time_format_from_the_palette():
    app = make_app(50)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("ctrl+p")
        await type_text(pilot, "time: date and")
        await pilot.press("enter")
        await pilot.pause()
        line_with(app, "Date and time UTC")
        line_with(app, "2026-11-18 11:06:46.713")  # the last row


async def test_remapped_navigation_keys_work_and_help_names_them(tmp_path):
    keys = tmp_path / "config" / "console-tui" / "keys.toml"
    keys.parent.mkdir(parents=True)
    keys.write_text('[nav]\nnext_error = "ctrl+e"\nfind = "F"\n')
    app = make_app(100)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.press("home", "e")
        await pilot.pause()
        assert number_of(cursor_line(app)) == "1", "e no longer jumps"
        await pilot.press("ctrl+e")
        await pilot.pause()
        assert "ERROR" in cursor_line(app)
        await pilot.press("question_mark")
        await until(pilot, lambda: "Change keys in" in screen_text(app), what="the help")
        for _ in range(60):  # scroll the help down to the keys that find your way
            if "nav.next_error" in screen_text(app):
                break
            await pilot.press("down")
            await pilot.pause()
        line_with(app, "Find your way")
        help_line = line_with(app, "Next ERROR or worse")[1]
        assert "^e" in help_line and "nav.next_error" in help_line
        assert line_with(app, "nav.find")[1].split("█")[1].split()[0] == "F"


def test_no_key_is_bound_twice_where_the_table_has_the_focus():
    """The table's keys and the app's (console, finding your way) never share a key; Esc is
    the one key that does several things, each only when it has something to do (and space
    is one binding id in two states, Pause and Resume, one shown at a time)."""
    from console_tui.ui.keys import binding_keys
    from console_tui.ui.widgets.log_table import LogTable

    seen: dict[str, Binding] = {}
    for binding in [*LogTable.BINDINGS, *ConsoleApp.BINDINGS]:
        for key in binding_keys(binding, {}):
            if key == "escape" or (key in seen and binding.id is not None and seen[key].id == binding.id):
                continue
            assert key not in seen, f"{key} is bound to {seen[key].action} and {binding.action}"
            seen[key] = binding
