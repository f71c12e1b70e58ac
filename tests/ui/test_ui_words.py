"""What the screen says: the footer names what space does now, counts agree with their nouns,
and ``--help`` points at text that exists."""

from __future__ import annotations

import pytest

from console_tui.cli import build_parser
from console_tui.model.store.record import LogRecord

from support.ui import line_with, make_app, screen_text, type_text, until


def footer(app) -> str:
    lines = [line for line in screen_text(app).splitlines() if "c Clear" in line]
    return lines[0] if lines else ""


async def test_the_footer_says_resume_while_paused():
    app = make_app(20)
    async with app.run_test(size=(120, 30)) as pilot:
        await until(pilot, lambda: "space Pause" in footer(app), what="the footer")
        assert "Resume" not in footer(app)
        await pilot.press("space")
        await until(pilot, lambda: "space Resume" in footer(app), what="the footer to say Resume")
        assert "Pause" not in footer(app) and "PAUSED" in screen_text(app)
        await pilot.press("space")
        await until(pilot, lambda: "space Pause" in footer(app), what="the footer to say Pause again")
        assert "PAUSED" not in screen_text(app)


async def test_a_remapped_pause_key_resumes_too(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    (tmp_path / "console-tui").mkdir()
    (tmp_path / "console-tui" / "keys.toml").write_text('[console]\npause = "p"\n')
    app = make_app(20, keymap_file=str(tmp_path / "console-tui" / "keys.toml"))
    async with app.run_test(size=(100, 30)) as pilot:
        await until(pilot, lambda: "p Pause" in footer(app), what="the footer to name the remapped key")
        assert footer(app).index("⏎ Details") < footer(app).index("p Pause") < footer(app).index("c Clear")  # in place
        await pilot.press("p")
        await until(pilot, lambda: "p Resume" in footer(app), what="the footer to say Resume")
        await pilot.press("p")
        await until(pilot, lambda: "PAUSED" not in screen_text(app), what="the view to resume")


async def test_the_detail_view_counts_one_line_as_one_line():
    app = make_app(0)
    app.main.intake.add_records([LogRecord(1_700_000_000_000_000_000, 20, "talker", "one")])
    async with app.run_test(size=(120, 40)) as pilot:
        await pilot.press("enter")
        await until(pilot, lambda: "Length" in screen_text(app), what="the details")
        assert line_with(app, "Length")[1].split("Length", 1)[1].strip(" █│▌▐") == "3 characters, 1 line"


def test_help_points_at_the_query_syntax_that_exists():
    from console_tui.commands.arguments import DOCS_URL

    text = " ".join(build_parser().format_help().split())
    assert "docs/rules.md" not in text and "README" not in text  # neither is where an installed user is
    assert "'The query line' in the documentation" in text and f"{DOCS_URL}rules/#the-query-line" in text


@pytest.mark.parametrize(("count", "words"), [(1, "1 rule"), (2, "2 rules")])
async def test_the_query_line_counts_its_rules(count, words):
    app = make_app(20)
    async with app.run_test(size=(120, 30)) as pilot:
        await pilot.press("slash")
        await type_text(pilot, "level>=warn" if count == 1 else "level>=warn -node:x")
        await until(pilot, lambda: words in screen_text(app), what=words)


async def test_the_palette_offers_one_entry_for_the_keys():
    """Textual's own "Keys" entry gave way to the help screen: typing "key" finds one entry."""
    app = make_app(5)
    async with app.run_test(size=(100, 30)) as pilot:
        await pilot.press("ctrl+p")
        await type_text(pilot, "key")
        await until(pilot, lambda: "Help: every key" in screen_text(app), what="the help entry")
        lines = [line.strip() for line in screen_text(app).splitlines()]
        entries = [line for line in lines if line.startswith(("Help", "Keys"))]
        assert entries == ["Help: every key"], entries
