"""The table at 80x24 as a person reads it: the row number, the time, the severity word, a node
name that tells nodes apart, and the message; and with a side pane open, severity, node and
message."""

from __future__ import annotations

import pytest

from support.feed import NODES
from support.ui import make_app, screen_text, until

SEVERITIES = {"DEBUG", "INFO", "WARN", "ERROR", "FATAL"}


def table_lines(app) -> list[str]:
    """The table's lines on the screen (its header first), cut to the table's own columns."""
    region = app.main.table.region
    return [line[region.x : region.right] for line in screen_text(app).splitlines()[region.y : region.bottom]]


def rows_with_severity_at(app, index: int) -> list[list[str]]:
    """The table's rows, split into words, whose word ``index`` is a severity."""
    rows = [line.split() for line in table_lines(app)[1:]]
    return [words for words in rows if len(words) > index + 2 and words[index] in SEVERITIES]


async def test_80x24_shows_number_time_severity_a_telling_node_name_and_the_message():
    app = make_app(200)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: len(rows_with_severity_at(app, 2)) >= 10, what="the rows")
        header = table_lines(app)[0].split()
        assert header == ["#", "Time", "UTC", "Sev", "Node", "Message"]  # times in UTC: its title says so
        rows = rows_with_severity_at(app, 2)
        for words in rows:
            assert "…" not in words[3], f"a node name cut at its end: {words[3]}"
        shown = {words[3] for words in rows}
        # Five nodes, five names, each its own: the end that tells them apart is kept.
        assert shown == {
            "count_and_log",
            "navigation.planner",
            "n.planner.costmap",
            "sensors.lidar_driver",
            "p.battery_monitor",
        }


@pytest.mark.parametrize("pane", ["r", "l"])
async def test_80x24_with_a_side_pane_keeps_severity_node_and_message(pane):
    app = make_app(200)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.press(pane)
        table = app.main.table
        await until(pilot, lambda: table.size.width < 60, what="the pane to open")
        await until(pilot, lambda: len(rows_with_severity_at(app, 0)) >= 10, what="the rows beside the pane")
        assert table_lines(app)[0].split()[:3] == ["Sev", "Node", "Message"]
        names = {words[1] for words in rows_with_severity_at(app, 0)}
        assert len(names) == len(NODES), names  # still five different names for five nodes
