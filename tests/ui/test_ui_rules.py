"""Pilot tests of the rules in the app: query line, rules pane, editor, quick rules, files."""

from __future__ import annotations

from functools import partial

import pytest

from console_tui.cli import build_parser, check_rule_arguments
from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import Role
from console_tui.model.rules.rulesfile import last_rules_path, query_history_path
from console_tui.ui.app import ConsoleApp
from console_tui.ui.screens.file_dialogs import PathScreen
from console_tui.ui.screens.quick_rule import QuickRuleScreen
from console_tui.ui.screens.rule_editor import RuleEditor

from support import ui
from support.feed import NODES, records
from support.ui import (
    frame_drawn,
    line_with,
    run_command,
    screen_text,
    steady_cursors,
    style_at,
    table_rows,
    toasts,
    type_text,
    until,
)

make_app = partial(ui.make_app, count=300)


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    """Rule sets and query history of these tests stay in a folder of their own."""
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    monkeypatch.setenv("XDG_STATE_HOME", str(tmp_path / "state"))


def shown(app: ConsoleApp) -> list:
    return [app.main.store.get(app.main.view.seq_at(row)) for row in range(len(app.main.view))]


async def type_query(pilot, app: ConsoleApp, text: str) -> None:
    """Open the query line, empty it (it opens with the query in force), type ``text`` key
    by key, and see it on the screen."""
    await pilot.press("slash")
    steady_cursors(app)
    await pilot.press("end", "ctrl+u")
    await type_text(pilot, text)
    await pilot.pause()
    line_with(app, text)


def looks(app: ConsoleApp, column: int = 60) -> dict[int, tuple]:
    """How each table row on the screen is painted: the colours of a cell in its message."""
    return {
        number: (style_at(app, column, y).color, style_at(app, column, y).bgcolor)
        for number, (y, _) in table_rows(app).items()
    }


async def test_query_line_applies_and_replaces_its_rules():
    app = make_app()
    async with app.run_test(size=(160, 40)) as pilot:
        await type_query(pilot, app, "level>=warn node:nav*")
        await pilot.press("enter")
        assert not app.main.query_bar.is_open and app.main.table.has_focus
        rows = shown(app)
        assert rows and all(r.level >= 30 and r.node.startswith("nav") for r in rows)
        await pilot.pause()
        assert f"{len(rows)}/300 shown" in screen_text(app) and "level>=warn node:nav*" not in screen_text(app)
        painted = [line for _, line in table_rows(app).values()]
        assert painted and all(line.split()[3].startswith("navigation") for line in painted)
        assert all(line.split()[2] in ("WARN", "ERROR", "FATAL") for line in painted)
        await type_query(pilot, app, "-level:debug")
        await pilot.press("enter")
        assert len(app.main.filtering.rules.entries) == 1  # the previous query's rule was replaced
        assert all(r.level != 10 for r in shown(app)) and len(shown(app)) == 270
        await pilot.pause()
        assert "270/300 shown" in screen_text(app)
        assert "DEBUG" not in {line.split()[2] for _, line in table_rows(app).values()}


async def test_invalid_query_shows_where_and_keeps_the_rules_in_force():
    app = make_app()
    async with app.run_test(size=(160, 40)) as pilot:
        await type_query(pilot, app, "level>=warn")
        await pilot.press("enter")
        before = len(app.main.view)
        await type_query(pilot, app, "level>=loud /time(out/")
        y, line = line_with(app, "level>=loud /time(out/")
        caret_row = next(row for row in screen_text(app).splitlines()[y + 1 :] if "^ " in row)
        column = caret_row.index("^")
        assert line[column : column + 4] == "loud", "the caret under the unknown level"
        assert "loud" in caret_row and "the rules in force stay" in screen_text(app)
        await pilot.press("enter")
        assert app.main.query_bar.is_open  # not applied
        assert len(app.main.view) == before and app.main.query_bar.applied_text == "level>=warn"
        await pilot.press("escape")
        assert not app.main.query_bar.is_open and len(app.main.view) == before


async def test_query_history_walks_back_and_is_kept_between_runs(tmp_path):
    app = make_app(remember_rules=True)
    async with app.run_test(size=(160, 40)) as pilot:
        for text in ("level:error", "node:count*", "-msg:scan"):
            await type_query(pilot, app, text)
            await pilot.press("enter")
        await pilot.press("slash")
        steady_cursors(app)
        await pilot.press("up")
        assert line_with(app, "node:count*") and "-msg:scan" not in screen_text(app)  # the current one was shown
        await pilot.press("up")
        assert line_with(app, "level:error") and "node:count*" not in screen_text(app)
        await pilot.press("down", "down")
        assert line_with(app, "-msg:scan") and "level:error" not in screen_text(app)
        await pilot.press("escape")
        assert "-msg:scan" not in screen_text(app), "the query line is closed"
    # Kept as state, in $XDG_STATE_HOME, not with the settings.
    state = tmp_path / "state" / "console-tui"
    assert (query_history_path(), last_rules_path()) == (state / "query-history.txt", state / "last-rules.toml")
    assert query_history_path().read_text().split("\n")[:3] == ["level:error", "node:count*", "-msg:scan"]
    assert 'kind = "message"' in last_rules_path().read_text() and "scan" in last_rules_path().read_text()
    assert not (tmp_path / "config" / "console-tui" / "last-rules.toml").exists()


async def test_query_given_at_start():
    plain = make_app()
    async with plain.run_test(size=(160, 40)) as pilot:
        await pilot.pause()
        before = looks(plain)
    app = make_app(query="+level:fatal")
    async with app.run_test(size=(160, 40)) as pilot:
        await pilot.pause()
        after = looks(app)
        rows = table_rows(app)
        assert "300/300 shown" in screen_text(app) and rows.keys() == before.keys()
        cursor = max(rows)  # following: the newest row has the cursor
        fatal = {n for n, (_, line) in rows.items() if line.split()[2] == "FATAL"}
        assert fatal and cursor in fatal
        for number in rows:
            if number == cursor:
                continue
            color, background = after[number]
            if number in fatal:  # highlighted: a background of its own, text as bright as before
                assert background != before[number][1] and color == before[number][0], number
            else:  # dimmed: the same background, fainter text
                assert background == before[number][1] and color != before[number][0], number
        await pilot.press("slash")
        assert line_with(app, "+level:fatal"), "the query line opens with the query in force"


async def add_rule(pilot, app: ConsoleApp, kind: str, fill: dict[str, object], role: str = "exclude") -> None:
    """Through the rules pane: a, choose the kind, fill the fields, ctrl+s (Apply)."""
    if not app.main.rules_pane.is_open:
        await pilot.press("r")
    await pilot.press("a")
    await until(pilot, lambda: isinstance(app.screen, RuleEditor), what="the rule editor")
    editor = app.screen
    assert isinstance(editor, RuleEditor)
    editor.query_one("#kind").value = kind
    await pilot.pause()
    for name, value in fill.items():
        widget = editor.query_one(f"#{name}")
        widget.value = value
    if role == "highlight":
        editor.query_one("RadioButton[name='highlight']").value = True
    await pilot.pause()
    await pilot.press("ctrl+s")
    await frame_drawn(pilot)  # the editor closed, or its error shown


@pytest.mark.parametrize(
    "kind, fill, check",
    [
        ("message", {"message-text": "scan"}, lambda r: "scan" not in r.msg),
        ("message", {"message-text": r"^\d+ is", "message-regex": True}, lambda r: not r.msg[0].isdigit()),
        ("severity", {"severity-info": True, "severity-debug": True}, lambda r: r.level >= 30),
        ("node", {"node-names": "navigation.*, count_and_log"}, lambda r: r.node.startswith(("sensors", "power"))),
        ("location", {"location-file": "planner.cpp"}, lambda r: "planner.cpp" not in r.file),
        ("location", {"location-line": "47"}, lambda r: r.line != 47),
        ("time", {"time-from": "1795000010", "time-to": ""}, lambda r: r.stamp_ns < 1795000010_000_000_000),
        (
            "custom",
            {"node-names": "count_and_log", "severity-info": True},
            lambda r: not (r.node == "count_and_log" and r.level == 20),
        ),
    ],
)
async def test_every_kind_of_rule_through_the_editor(kind, fill, check):
    app = make_app()
    async with app.run_test(size=(160, 45)) as pilot:
        await add_rule(pilot, app, kind, fill)
        assert len(app.main.filtering.rules.entries) == 1 and app.main.filtering.rules.entries[0].rule.kind == kind
        rows = shown(app)
        assert 0 < len(rows) < 300 and all(check(r) for r in rows)
        await pilot.pause()
        assert f"{len(rows)}/300 shown" in screen_text(app)
        listed = app.main.filtering.rules.entries[0].describe()[:20]
        assert listed in screen_text(app), f"the rules pane lists {listed!r}"


async def test_an_invalid_regex_is_refused_in_the_editor_and_nothing_changes():
    app = make_app()
    async with app.run_test(size=(160, 45)) as pilot:
        await add_rule(pilot, app, "message", {"message-text": "time(out", "message-regex": True})
        assert isinstance(app.screen, RuleEditor)
        error_row = line_with(app, "invalid regular expression 'time(out'")[1]
        assert "missing )" in error_row
        assert not app.main.filtering.rules.entries and len(app.main.view) == 300
        await pilot.press("escape")
        assert not isinstance(app.screen, RuleEditor)
        assert "300/300 shown" in screen_text(app) and "invalid regular expression" not in screen_text(app)


def pane_rule(app: ConsoleApp) -> str:
    """The rules pane's first rule as the screen shows it (the pane's column only)."""
    return " ".join(line_with(app, "▊●" if "▊●" in screen_text(app) else "▊○")[1].split("▕")[0].split())


def status(app: ConsoleApp) -> str:
    return screen_text(app).splitlines()[-2]


async def test_rules_pane_switches_inverts_changes_role_edits_and_deletes():
    app = make_app()
    async with app.run_test(size=(160, 45)) as pilot:
        await add_rule(pilot, app, "severity", {"severity-debug": True})
        await until(pilot, lambda: "270/300 shown" in status(app), what="the rule in force")
        assert pane_rule(app) == "▊● hide severity DEBUG 30▎", "on, and the count at the right"
        assert "1 rule" in status(app)
        await pilot.press("space")
        await until(pilot, lambda: "300/300 shown" in status(app), what="the rule switched off")
        assert pane_rule(app).startswith("▊○ hide severity DEBUG") and "rules off" in status(app)
        await pilot.press("space", "i")
        await until(pilot, lambda: "30/300 shown" in status(app), what="the rule inverted")
        assert pane_rule(app).startswith("▊● hide not severity DEBUG")
        await pilot.press("i", "h")
        await until(pilot, lambda: "mark severity DEBUG" in pane_rule(app), what="a highlight rule")
        await until(pilot, lambda: "300/300 shown" in status(app), what="every row shown")
        assert "1 rule" in status(app), "in force (highlighted rows on the screen: test_query_given_at_start)"
        await pilot.press("e")
        await until(pilot, lambda: "Edit rule" in screen_text(app), what="the rule editor")
        await pilot.click("#severity-warn")
        await pilot.press("ctrl+s")
        await until(pilot, lambda: "Edit rule" not in screen_text(app), what="the editor closed")
        await until(pilot, lambda: "WARN" in pane_rule(app), what="the changed rule in the pane")
        assert "DEBUG" in pane_rule(app)
        await pilot.press("d")
        await until(pilot, lambda: "No rules." in screen_text(app), what="the rule deleted")
        assert "rule" not in status(app).replace("Rules", "")


async def test_quick_rules_from_a_row():
    app = make_app()
    async with app.run_test(size=(160, 45)) as pilot:
        row = app.main.store.get(app.main.table.cursor_seq)
        await pilot.press("minus")
        assert isinstance(app.screen, QuickRuleScreen)
        await pilot.press("enter")  # the first choice: this node
        await until(pilot, lambda: "240/300 shown" in screen_text(app), what="the rule in force")
        assert all(r.node != row.node for r in shown(app)) and len(app.main.view) == 240
        await pilot.press("plus", "down", "enter")  # highlight this severity
        assert app.main.filtering.rules.entries[-1].role is Role.HIGHLIGHT
        seq = app.main.view.seq_at(len(app.main.view) - 1)
        expected = (
            "highlight"
            if app.main.store.get(seq).level == app.main.store.get(app.main.table.cursor_seq).level
            else "dim"
        )
        assert app.main.view.decoration_of(seq) == expected


async def test_quick_rules_from_selected_rows():
    app = make_app()
    async with app.run_test(size=(160, 45)) as pilot:
        await pilot.press("shift+up", "shift+up", "shift+up")
        assert len(app.main.table.selected_rows()) == 4
        rows = [app.main.store.get(seq) for seq in app.main.table.selected_seqs(10)]
        nodes = {row.node for row in rows}
        await pilot.press("minus")
        assert isinstance(app.screen, QuickRuleScreen)
        await pilot.press("enter")  # the first choice: these nodes
        assert app.main.filtering.rules.entries[-1].rule.names == tuple(dict.fromkeys(row.node for row in rows))
        assert all(r.node not in nodes for r in shown(app))
        await pilot.press("up", "shift+up", "escape")  # a plain move and Esc end a selection
        assert len(app.main.table.selected_rows()) == 1


async def test_highlighted_only_switch():
    app = make_app(query="+level:error,fatal")
    async with app.run_test(size=(160, 45)) as pilot:
        await pilot.pause()
        assert len(app.main.view) == 300
        await pilot.press("H")
        assert app.main.filtering.rules.highlighted_only and {r.level for r in shown(app)} == {40, 50}
        await pilot.pause()
        assert "60/300 shown" in screen_text(app)
        assert {line.split()[2] for _, line in table_rows(app).values()} == {"ERROR", "FATAL"}
        await pilot.press("H")
        assert len(app.main.view) == 300
        await pilot.pause()
        assert "300/300 shown" in screen_text(app)


async def test_rule_sets_save_and_load_and_a_bad_file_changes_nothing(tmp_path):
    app = make_app(query=f"-node:{NODES[0]} +level:warn")
    target = tmp_path / "rules.toml"
    async with app.run_test(size=(160, 45), notifications=True) as pilot:
        await pilot.pause()
        saved = app.main.filtering.rules
        await pilot.press("r")
        await pilot.press("S")
        assert isinstance(app.screen, PathScreen)
        app.screen.query_one("#path").value = str(target)
        await pilot.press("enter")
        assert target.exists()
        await run_command(pilot, "Clear rules")
        await until(pilot, lambda: "No rules." in screen_text(app), what="the rules cleared")
        assert not app.main.filtering.rules.entries and len(app.main.view) == 300
        await pilot.press("O")
        app.screen.query_one("#path").value = str(target)
        await pilot.press("enter")
        await pilot.pause()
        assert [e.describe() for e in app.main.filtering.rules.entries] == [e.describe() for e in saved.entries]
        bad = tmp_path / "bad.toml"
        bad.write_text('[[rules]]\nkind = "severity"\nlevels = ["warm"]\n')
        before = app.main.filtering.rules
        await pilot.press("O")
        app.screen.query_one("#path").value = str(bad)
        await pilot.press("enter")
        await until(pilot, lambda: any("warm" in toast for toast in toasts(app)), what="the file's problem")
        assert app.main.filtering.rules == before


async def test_rule_changes_over_a_large_store_refilter_in_the_background():
    app = make_app(count=200_000)
    async with app.run_test(size=(160, 45)) as pilot:
        await pilot.pause()
        app.main.filtering.apply_rules(app.main.filtering.rules.with_query(parse_query("-level:info")))
        # Straight after the change: the newest screen is right, the rest is still to do.
        assert app.main.view.refiltering
        bottom = [
            app.main.store.get(app.main.view.seq_at(row)) for row in range(len(app.main.view) - 40, len(app.main.view))
        ]
        assert len(bottom) == 40 and all(r.level != 20 for r in bottom)
        cursor = app.main.table.cursor_row
        await pilot.press("up")  # keys are answered meanwhile
        assert app.main.table.cursor_row != cursor
        await until(pilot, lambda: not app.main.view.refiltering)
        info_per_ten = sum(1 for r in records(10) if r.level == 20)
        assert len(app.main.view) == 200_000 - info_per_ten * 20_000


def test_rules_last_at_start_restores_the_saved_set(tmp_path):
    parser = build_parser()
    args = parser.parse_args(["--rules", "last"])
    with pytest.raises(SystemExit):
        check_rule_arguments(parser, args)  # nothing saved yet: a clear error, exit 2
    last_rules_path().parent.mkdir(parents=True, exist_ok=True)
    last_rules_path().write_text('[[rules]]\nkind = "severity"\nlevels = ["debug"]\n')
    args = parser.parse_args(["--rules", "last"])
    check_rule_arguments(parser, args)
    assert args.rule_set.entries[0].rule.levels == frozenset({10})


def test_quick_rules_for_several_rows():
    from console_tui.model.store.record import LogRecord
    from console_tui.ui.screens.quick_rule import quick_rules

    rows = [
        LogRecord(stamp_ns=1, level=30, node="nav", msg="a (b)?", file="x.py", function="f", line=1),
        LogRecord(stamp_ns=2, level=40, node="cam", msg="c|d", file="y.py", function="g", line=2),
        LogRecord(stamp_ns=3, level=30, node="nav", msg="a (b)?", file="x.py", function="f", line=1),
    ]
    labels, rules = zip(*quick_rules(rows), strict=False)
    assert labels[0] == "these 2 nodes: nav, cam" and rules[0].names == ("nav", "cam")
    assert labels[1] == "these 2 severities: WARN, ERROR" and rules[1].levels == frozenset({30, 40})
    assert labels[2].startswith("these 2 messages")
    assert [rules[2].matches(row) for row in rows] == [True, True, True]
    assert not rules[2].matches(LogRecord(stamp_ns=4, level=20, node="n", msg="a b"))
    assert len(rules) == 3  # two locations: no location rule
    assert [label.split(":")[0] for label, _ in quick_rules(rows[:1])] == [
        "this node",
        "this severity",
        "this message",
        "this location",
    ]
