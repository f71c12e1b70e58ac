"""Hostile rules (issue 17): a catastrophic regex must not freeze the app, a long filtering
stops on Esc, and a rules file nested 100k deep is refused with a clear message."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest
from textual.widgets import Input

from console_tui.model.rules import MessageRule
from console_tui.model.rules.rule import RuleError
from console_tui.model.rules.rulesfile import load_rules
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord
from console_tui.ui.app import ConsoleApp
from console_tui.ui.controllers import rules as rule_control
from console_tui.ui.screens.help import HelpScreen

from support.clock import TickingClock
from support.ui import screen_text, type_text, until

HOSTILE = "a" * 30 + "b"  # /(a+)+$/ backtracks 2**30 ways on each of these


def hostile_app(count: int) -> ConsoleApp:
    """``count`` hostile messages, every one its own row (two texts in turn: no storm collapses them)."""
    store = LogStore()
    store.extend_records(
        LogRecord(stamp_ns=1_795_000_000_000_000_000 + i, level=20, node="n", msg=HOSTILE + "b" * (i % 2))
        for i in range(count)
    )
    return ConsoleApp(store=store, utc=True)


@pytest.mark.timeout(60)  # before the fix: frozen for minutes, ended by this timeout
@pytest.mark.parametrize("how", ["query", "rules file"])
async def test_a_catastrophic_regex_never_freezes_the_app(how, tmp_path):
    app = hostile_app(100_000)
    async with app.run_test(size=(120, 30), notifications=True) as pilot:
        await pilot.pause()
        row = app.main.table.cursor_row
        # The work the app does from the rule change to answering a key, in CPU seconds: on
        # this shared machine wall time depends on the neighbours, CPU time on the app.
        began = time.process_time()
        if how == "query":
            await pilot.press("slash")
            await type_text(pilot, "/(a+)+$/")
            began = time.process_time()
            await pilot.press("enter", "up")
        else:
            path = tmp_path / "rules.toml"
            path.write_text('[[rules]]\nkind = "message"\ntext = "(a+)+$"\nregex = true\n')
            await pilot.press("r", "O")  # the rules pane's Open rule set
            app.screen.query_one("#path", Input).value = str(path)
            began = time.process_time()
            await pilot.press("enter", "escape", "up")  # loaded, back to the table, a key
        await until(pilot, lambda: app.main.table.cursor_row == row - 1, timeout=10, what="the key's effect")
        # Under 1 s of CPU run alone; the suite's coverage tracing doubles that. Before the fix:
        # minutes (the timeout above ended it).
        assert time.process_time() - began < 3.0
        await until(pilot, lambda: "Rule switched off" in screen_text(app), timeout=5, what="the notification")
        assert "too slow" in screen_text(app)
        assert not app.main.filtering.rules.entries[0].enabled
        assert not app.main.view.refiltering and len(app.main.view) == 100_000
        await pilot.press("question_mark")  # and the app goes on answering
        await until(pilot, lambda: isinstance(app.screen, HelpScreen), timeout=10, what="the help screen")


async def test_esc_stops_a_long_filtering(monkeypatch):
    # A slice walks one piece (the view's clock moves 1 ms a reading, past the budget) and the
    # slices are 0.2 s apart: filtering 200,000 records takes many seconds on any machine.
    monkeypatch.setattr(rule_control, "REFILTER_BUDGET_S", 0.0005)
    monkeypatch.setattr(rule_control, "REFILTER_PAUSE_S", 0.2)
    store = LogStore()
    store.extend_records(LogRecord(stamp_ns=i, level=20, node="n", msg=f"message {i}") for i in range(200_000))
    app = ConsoleApp(store=store, utc=True)
    app.main.view.clock = TickingClock(0.001)
    async with app.run_test(size=(120, 30), notifications=True) as pilot:
        await pilot.press("slash")
        await type_text(pilot, '-"message 1"')
        await pilot.press("enter")
        await until(pilot, lambda: "filtering" in screen_text(app), timeout=30, what="the filtering shown")
        assert app.main.filtering.rules.entries[0].rule == MessageRule("message 1", ignore_case=True)
        assert app.main.view.refiltering
        await pilot.press("escape")
        await until(pilot, lambda: not app.main.view.refiltering, timeout=5, what="filtering to stop")
        assert not app.main.filtering.rules.entries[0].enabled
        await until(pilot, lambda: "Filtering stopped" in screen_text(app), timeout=5, what="the notification")
        assert len(app.main.view) == 200_000


def test_a_rules_file_nested_100k_deep_is_refused(tmp_path):
    path = tmp_path / "deep.toml"
    path.write_text("x = " + "[" * 100_000 + "]" * 100_000 + "\n")
    with pytest.raises(RuleError) as caught:
        load_rules(path)
    assert "deep.toml" in caught.value.message and "nested" in caught.value.message
    result = subprocess.run(
        [sys.executable, "-m", "console_tui", "--rules", str(path)], capture_output=True, text=True, timeout=60
    )
    assert result.returncode == 2
    assert "Traceback" not in result.stderr and "nested" in result.stderr
