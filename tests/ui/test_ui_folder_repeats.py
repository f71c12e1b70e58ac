"""A run's folder opened whole (issue 28): the rosout log and the nodes' own log files hold the
same messages; each is one row, whose details name both files, and the load summary says how
many were merged. On 20,213 rosout.log lines with 330 storms of 50 repeats, and the nodes'
console output beside it (19,800 lines)."""

from __future__ import annotations

import pytest

from console_tui.ui.app import ConsoleApp

from support.storm_log import write_node_logs, write_storm_log
from support.ui import screen_text, table_rows, until

LINES = 20_213
NODE_LINES = 19_800


def status(app) -> str:
    return screen_text(app).splitlines()[app.main.status_bar.region.y]


def toast(app) -> str:
    """The notifications' words on the screen, in one line (what follows a toast's edge, ▌)."""
    return " ".join(" ".join(line.rsplit("▌", 1)[1].split()) for line in screen_text(app).splitlines() if "▌" in line)


def flat(app) -> str:
    """The screen's words, in one line (a notification wraps its text)."""
    return " ".join(screen_text(app).split())


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_a_run_folder_shows_each_message_once(tmp_path, size):
    run = tmp_path / "run"
    run.mkdir()
    assert write_storm_log(run / "rosout.log") == LINES
    assert write_node_logs(run) == NODE_LINES
    app = ConsoleApp(files=[str(run)], utc=True)
    async with app.run_test(size=size, notifications=True) as pilot:
        await until(pilot, lambda: "repeats merged" in toast(app), what=lambda: screen_text(app))
        summary = toast(app)
        assert f"Loaded {LINES:,} records from 3 files, {NODE_LINES:,} repeats merged" in summary
        await until(pilot, lambda: f"{LINES:,}/{LINES:,} shown" in status(app), what=lambda: status(app))
        await until(pilot, lambda: "merged" not in toast(app), what="the summary to go (it covers rows at 80 columns)")
        await until(pilot, lambda: "330 storms" in status(app), what=lambda: status(app))
        rows = [line for _, line in table_rows(app).values()]
        assert sum("heard 3300" in line for line in rows) == 1, "\n".join(rows)
        assert any("×50" in line and "burst 329" in line for line in rows)
        await pilot.press("up", "up", "enter")  # the details of "heard 3300" (the newest rows: /planner's)
        await until(pilot, lambda: "heard 3300" in flat(app) and "Function" in flat(app), what="the details")
        assert "rosout.log + listener-2-stdout.log" in flat(app)
        assert "listener.py" in screen_text(app)  # the rosout copy: where it was logged
