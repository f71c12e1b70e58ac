"""A log warehouse on the command line beside files, as every command reads it (the one
dispatch of positional arguments): ``tail`` and ``convert`` merge its rows with a file's by
time, each once, its rules gone down into SQL; the app (``cli.main``, headless) shows both."""

from __future__ import annotations

import json
import re
import subprocess
import sys

import pytest

from console_tui.model.formats import save_records
from console_tui.model.store.record import LogRecord

from support.run_main import run_main
from support.ui import screen_text, until
from support.warehouse import chdb_address, needs_store, ship_records

pytestmark = needs_store

T0 = 1_765_000_000_000_000_000


@pytest.fixture
def warehouse_and_file(tmp_path):
    """A warehouse's rows at even 10 ms steps (robot cart), a file's at odd ones (no robot)."""
    address = chdb_address(tmp_path / "warehouse")
    ship_records(
        address, [LogRecord(T0 + 2 * i * 10_000_000, 30, "nav", f"stored {i}", robot="cart") for i in range(20)]
    )
    path = tmp_path / "copied.jsonl"
    save_records([LogRecord(T0 + (2 * i + 1) * 10_000_000, 20, "arm", f"filed {i}") for i in range(20)], path, "jsonl")
    return address, path


def run(*argv: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "console_tui", *argv], capture_output=True, text=True, timeout=120, errors="replace"
    )


def test_tail_and_convert_merge_a_warehouse_and_a_file_by_time(warehouse_and_file, tmp_path):
    address, path = warehouse_and_file
    tail = run("tail", address.text, str(path), "--json")
    assert tail.returncode == 0, tail.stderr
    printed = [json.loads(line) for line in tail.stdout.splitlines()]
    assert [p["msg"] for p in printed] == [f"{kind} {i}" for i in range(20) for kind in ("stored", "filed")]
    assert {p.get("robot", "") for p in printed if p["msg"].startswith("stored")} == {"cart"}
    only = run("tail", address.text, str(path), "--json", "--query", "robot:cart")
    assert [json.loads(line)["msg"] for line in only.stdout.splitlines()] == [f"stored {i}" for i in range(20)]
    out = tmp_path / "both.jsonl"
    converted = run("convert", address.text, str(path), "-o", str(out))
    assert converted.returncode == 0, converted.stderr
    assert [json.loads(line)["msg"] for line in out.read_text().splitlines()] == [p["msg"] for p in printed]
    window = run("convert", address.text, "--since", str((T0 + 20 * 10_000_000) / 1e9), "--format", "jsonl", "-o", "-")
    assert [json.loads(line)["msg"] for line in window.stdout.splitlines()] == [f"stored {i}" for i in range(10, 20)]


def test_the_app_shows_a_warehouse_beside_a_file(warehouse_and_file, tmp_path, monkeypatch):
    address, path = warehouse_and_file
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    monkeypatch.setitem(sys.modules, "rclpy", None)  # no live source: files and the warehouse only
    seen: dict[str, str] = {}

    async def script(pilot) -> None:
        app = pilot.app
        await until(pilot, lambda: "40/40 shown" in screen_text(app), what=lambda: screen_text(app))
        seen["screen"] = screen_text(app)
        await pilot.press("q")

    code, _ = run_main(monkeypatch, [address.text, str(path), "--utc"], script, size=(120, 50))
    assert code == 0
    lines = [line for line in seen["screen"].splitlines() if re.search(r"(stored|filed) \d", line)]
    shown = [re.search(r"(stored|filed) \d+", line).group(0) for line in lines]
    assert shown[:4] == ["stored 0", "filed 0", "stored 1", "filed 1"]  # by time, each once
    assert len(shown) == len(set(shown)) and "cart" in lines[0] and "cart" not in lines[1]  # its Robot column
    assert "chdb://" in seen["screen"].splitlines()[-2]
