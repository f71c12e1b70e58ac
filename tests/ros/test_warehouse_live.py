"""A log warehouse beside the live stream (``console-tui chdb://DIR --live``, a real ROS 2
node in a process of its own): the warehouse's rows and the node's live message in one table,
and the status line naming both."""

from __future__ import annotations

import pytest

from console_tui.model.store.record import LogRecord

from support.run_main import run_main
from support.ui import line_with, screen_text, until
from support.warehouse import STORE_MISSING, chdb_address, ship_records

pytestmark = [pytest.mark.ros2, pytest.mark.skipif(bool(STORE_MISSING), reason=STORE_MISSING or "-")]


def test_a_warehouse_beside_the_live_stream(nodes, tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    for name in ("ROS_MASTER_URI", "ROS_VERSION"):
        monkeypatch.delenv(name, raising=False)
    address = chdb_address(tmp_path / "warehouse")
    ship_records(
        address, [LogRecord(1_765_000_000_000_000_000 + i, 40, "nav", f"stored {i}", robot="cart") for i in range(5)]
    )
    talker = nodes.start("talker.py", "--name", "live_talker")
    talker.expect("ready")
    seen: dict[str, str] = {}

    async def script(pilot) -> None:
        app = pilot.app
        await until(pilot, lambda: "stored 4" in screen_text(app), what="the warehouse's rows")
        await until(pilot, lambda: "/rosout 1 pub" in screen_text(app), what="the talker on /rosout")
        talker.send({"cmd": "log", "level": "error", "msg": "said live"})
        await until(pilot, lambda: "said live" in screen_text(app), what="the live message")
        seen["live"] = line_with(app, "said live")[1]
        seen["stored"] = line_with(app, "stored 4")[1]
        seen["status"] = screen_text(app).splitlines()[-2]
        await pilot.press("q")

    code, _ = run_main(monkeypatch, [address.text, "--live", "--topic", "/rosout", "--utc"], script, size=(160, 30))
    assert code == 0
    assert "live_talker" in seen["live"] and "cart" in seen["stored"]
    assert "ROS 2 domain" in seen["status"] and "chdb://" in seen["status"], seen["status"]
