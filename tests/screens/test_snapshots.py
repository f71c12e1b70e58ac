"""Snapshot tests of the real app on a deterministic feed (fixed stamps, shown in UTC)."""

from __future__ import annotations

import pytest

from console_tui.model.loggers.logger_levels import TemporaryLevel
from console_tui.model.store.log_store import LogStore
from console_tui.ui.app import ConsoleApp

from support.feed import PLANNER, feed_logger_pane, records


def feed_app(count: int = 200, **options) -> ConsoleApp:
    store = LogStore()
    store.extend_records(records(count))
    return ConsoleApp(store=store, utc=True, clock=lambda: 0.0, **options)  # a still clock: the rate reads 0/s


@pytest.mark.parametrize("size", [(80, 24), (160, 48)], ids=["80x24", "160x48"])
def test_table(snap_compare, size):
    assert snap_compare(feed_app(), terminal_size=size)


@pytest.mark.parametrize("size", [(80, 24), (160, 48)], ids=["80x24", "160x48"])
def test_scrolled_and_paused(snap_compare, size):
    async def scroll_pause_and_receive(pilot):
        await pilot.press("up", "up", "up", "space")
        pilot.app.main.intake.add_records(records(25, start=200))
        pilot.app.main.update_status()
        await pilot.pause()

    assert snap_compare(feed_app(), terminal_size=size, run_before=scroll_pause_and_receive)


def test_detail(snap_compare):
    assert snap_compare(feed_app(), terminal_size=(160, 48), press=["up", "up", "enter"])


def test_help(snap_compare, monkeypatch):
    monkeypatch.setenv("HOME", "/home/robot")  # the keymap file's place, shown as ~/.config/...
    monkeypatch.delenv("XDG_CONFIG_HOME")
    assert snap_compare(feed_app(), terminal_size=(80, 24), press=["question_mark"])


@pytest.mark.parametrize("size", [(80, 24), (160, 48)], ids=["80x24", "160x48"])
def test_logger_pane_beside_the_table(snap_compare, size):
    """The pane in a fixed state, fed as its LoggerControl would feed it (no live graph)."""

    async def open_pane_on_the_planner(pilot):
        pane = pilot.app.main.logger_pane
        await pilot.press("l")
        feed_logger_pane(pane)
        pane.show_temporaries([TemporaryLevel(PLANNER, "navigation.planner.costmap", 10, 0, deadline=25.0)])
        await pilot.press("right", "down")

    assert snap_compare(feed_app(), terminal_size=size, run_before=open_pane_on_the_planner)


def test_empty_table_shows_its_header(snap_compare):
    """The first frame before any message: the header row and the status line."""
    assert snap_compare(ConsoleApp(store=LogStore(), utc=True, clock=lambda: 0.0), terminal_size=(80, 24))


@pytest.mark.parametrize("size", [(80, 24), (160, 48)], ids=["80x24", "160x48"])
def test_highlighted_and_dimmed_rows(snap_compare, size):
    """Highlight rules on: matching rows marked, the others dimmed; an exclude rule hides some."""
    app = feed_app(query="+level:error,fatal +node:navigation.planner -msg:scan")  # as --query gives it
    assert snap_compare(app, terminal_size=size)


def test_rules_pane(snap_compare):
    async def open_pane_with_rules(pilot):
        from console_tui.model.rules import (
            MessageRule,
            NodeRule,
            RuleSet,
            SeverityRule,
            TimeRangeRule,
            exclude,
            highlight,
        )

        app = pilot.app
        app.main.filtering.apply_rules(
            RuleSet(
                (
                    exclude(NodeRule(("sensors.*",))),
                    exclude(MessageRule("costmap", ignore_case=True), enabled=False),
                    highlight(SeverityRule.at_least(40)),
                    highlight(MessageRule(r"time(out|d out)", ignore_case=True, regex=True), inverted=True),
                    exclude(TimeRangeRule(None, 1_795_000_005_000_000_000)),
                    exclude(MessageRule("")),
                )
            )
        )
        await pilot.press("r")
        await pilot.pause()

    assert snap_compare(feed_app(), terminal_size=(160, 48), run_before=open_pane_with_rules)
