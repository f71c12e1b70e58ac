"""The rules pane and the rule editor as a person reads them, at 100x30 and 80x24."""

from __future__ import annotations

import re

import pytest

from support.ui import make_app, screen_text, type_text, until

LONG_REGEX = r"/(timed out|time out|timeout) waiting for (costmap|map|transform \w+ to \w+)/"


@pytest.fixture(autouse=True)
def own_config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))


def pane_lines(app) -> list[str]:
    """The rules pane's column of the screen (left of its border)."""
    width = app.main.rules_pane.size.width
    return [line[:width] for line in screen_text(app).splitlines()]


async def test_an_empty_rules_pane_says_how_to_add_one():
    app = make_app(20)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("r")
        await until(pilot, lambda: "No rules." in screen_text(app), what="the empty pane's words")
        text = screen_text(app)
        assert "highlighted only: off" in text and "a adds one" in text


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_each_rule_has_its_count_on_its_first_line(size):
    app = make_app(300)
    async with app.run_test(size=size) as pilot:
        await pilot.press("slash")
        await type_text(pilot, f"level>=warn -node:count_and_log +{LONG_REGEX}")
        await pilot.press("enter")
        await pilot.press("r")
        await until(pilot, lambda: "● mark" in screen_text(app), what="the rules in the pane")
        await until(pilot, lambda: not app.main.view.refiltering, what="the counts")

        def firsts() -> list[str]:
            return [line for line in pane_lines(app) if re.search(r"● (hide|mark) ", line)]

        def counted(line: str) -> bool:
            return re.search(r" \d[\d,]*\s*[▎▌│]?\s*$", line) is not None

        await until(pilot, lambda: len(firsts()) == 3 and all(map(counted, firsts())), what=lambda: pane_lines(app))
        assert len(firsts()) == 3, pane_lines(app)
        for line in firsts():
            assert counted(line), f"no count at the end of {line!r}"
        # The long regex is shown whole, over several lines, rather than cut.
        joined = "".join(line.strip(" ▊▎") for line in pane_lines(app))
        assert "transform" in joined and r"\w+)/" in joined


@pytest.mark.parametrize("size", [(100, 30), (80, 24)])
async def test_a_long_regex_error_in_the_editor_is_shown_whole(size):
    app = make_app(20)
    async with app.run_test(size=size) as pilot:
        await pilot.press("r", "a")
        await until(pilot, lambda: "New rule" in screen_text(app), what="the rule editor")
        await pilot.press("tab", "tab", "tab")  # kind, exclude/highlight, inverted, the text
        await type_text(pilot, "(timed out|time out|timeout) waiting for (costmap|map|transform [a-")
        await pilot.press("tab", "tab", "space")  # ignore case, regular expression: on
        await pilot.press("f2")
        await until(pilot, lambda: "Not applied" in screen_text(app), what="the refusal")
        words = " ".join(screen_text(app).replace("▎", " ").replace("█", " ").split())
        assert "unterminated character set at position" in words, words
