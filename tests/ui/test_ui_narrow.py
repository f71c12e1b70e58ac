"""The table at 80x24 as a person reads it: the row number, the time, the severity word, a node
name that tells nodes apart, and the message; and with a side pane open, severity, node and
message."""

from __future__ import annotations

import pytest

from support.feed import NODES
from support.ui import make_app, screen_text, until

SEVERITIES = {"DEBUG", "INFO", "WARN", "ERROR", "FATAL"}


def table_rows(app, left: int = 0) -> list[list[str]]:
    """The table's rows on the screen, from column ``left``, split into words."""
    rows = []
    for line in screen_text(app).splitlines()[1:]:
        words = line[left:].split()
        if len(words) > 4 and words[2] in SEVERITIES:
            rows.append(words)
    return rows


async def test_80x24_shows_number_time_severity_a_telling_node_name_and_the_message():
    app = make_app(200)
    async with app.run_test(size=(80, 24)) as pilot:
        await pilot.pause()
        header = screen_text(app).splitlines()[0].split()
        assert header == ["#", "Time", "UTC", "Sev", "Node", "Message"]  # times in UTC: its title says so
        rows = table_rows(app)
        assert len(rows) >= 15
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
        await pilot.pause(0.3)
        table = app.table
        await until(pilot, lambda: table.size.width < 60, what="the pane to open")
        left = table.region.x
        header = screen_text(app).splitlines()[0][left:].split()
        assert header[:3] == ["Sev", "Node", "Message"]
        rows = [
            line[left:].split()
            for line in screen_text(app).splitlines()[1:]
            if line[left:].split()[:1] and line[left:].split()[0] in SEVERITIES
        ]
        assert len(rows) >= 10
        names = {words[1] for words in rows}
        assert len(names) == len(NODES), names  # still five different names for five nodes
