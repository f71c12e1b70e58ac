"""Severity reads at a glance in every colour mode: by its word and its weight, not only its hue.

The table's severity words and the status line's counts are read from the screen at 80x24;
their styles are read from the screen's cells too, and checked as a truecolor, a 16-colour and
a ``NO_COLOR`` terminal would show them.
"""

from __future__ import annotations

import re

from rich.color import ColorSystem
from rich.style import Style
from textual.color import Color

from console_tui.model.levels import SEVERITY_TABLE

from support.ui import make_app, screen_text, style_at, until

WORDS = [level.name for level in SEVERITY_TABLE]


def severity_cells(app) -> dict[str, Style]:
    """The style of each severity word as the screen shows it, on the table's rows away from
    the cursor's (its first letter's cell: a word is drawn in one style)."""
    table = app.main.table
    found: dict[str, Style] = {}
    lines = screen_text(app).splitlines()
    for y in range(table.region.y + 1, table.region.bottom):  # below the header
        if int(table.scroll_y) + (y - table.region.y) - 1 == table.cursor_row:
            continue
        for word in WORDS:
            at = f" {lines[y]} ".find(f" {word} ")
            if at >= 0 and word not in found:
                found[word] = style_at(app, at, y)
    return found


def brightness(style: Style, default: str) -> float:
    color = style.color
    return Color.parse(color.triplet.hex if color and color.triplet else default).brightness


async def test_the_severity_words_and_counts_show_at_80x24():
    app = make_app(30)
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: "D3 I15 W6 E3 F3" in screen_text(app), what="the status line's counts")
        lines = screen_text(app).splitlines()
        rows = "\n".join(lines[1:-2])
        for word in WORDS:
            assert f" {word} " in rows, f"{word} is not shown in the Sev column"
        status = lines[-2]
        assert "D3 I15 W6 E3 F3" in status, status
        cells = severity_cells(app)
        assert set(cells) == set(WORDS)
        for word in ("WARN", "ERROR", "FATAL"):
            assert cells[word].bold, f"{word} is drawn bold"
        assert not cells["INFO"].bold and not cells["DEBUG"].bold
        # A 16-colour terminal gets WARN and ERROR in different colours (they were both red).
        standard = {word: cells[word].color.downgrade(ColorSystem.STANDARD).number for word in ("WARN", "ERROR")}
        assert standard["WARN"] != standard["ERROR"], standard


async def test_without_colour_error_is_never_darker_than_info_and_weights_tell_them_apart(monkeypatch):
    monkeypatch.setenv("NO_COLOR", "1")
    app = make_app(30)
    assert app.no_color
    async with app.run_test(size=(80, 24)) as pilot:
        await until(pilot, lambda: len(severity_cells(app)) == len(WORDS), what="every severity in the table")
        cells = severity_cells(app)
        foreground = app.main.table.rich_style.color.triplet.hex
        assert brightness(cells["ERROR"], foreground) >= brightness(cells["INFO"], foreground)
        error, fatal, warn = cells["ERROR"], cells["FATAL"], cells["WARN"]
        assert warn.bold and error.bold and error.underline and fatal.bold and fatal.reverse
        lines = screen_text(app).splitlines()
        status_y = len(lines) - 2
        style = style_at(app, re.search(r" E\d", lines[status_y]).start() + 1, status_y)  # the status line's E count
        assert style.bold and style.color is not None and Color.parse(style.color.triplet.hex).brightness > 0.6, (
            "the E count stands out on the status line"
        )
