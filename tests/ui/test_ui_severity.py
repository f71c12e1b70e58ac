"""Severity reads at a glance in every colour mode: by its word and its weight, not only its hue.

The table's severity words and the status line's counts are read from the screen at 80x24;
their styles are read from what the table draws, and checked as a truecolor, a 16-colour and
a ``NO_COLOR`` terminal would show them.
"""

from __future__ import annotations

from rich.color import ColorSystem
from rich.segment import Segment
from textual.color import Color

from console_tui.model.levels import SEVERITY_TABLE

from support.ui import make_app, screen_text, until

WORDS = [level.name for level in SEVERITY_TABLE]


def severity_cells(app) -> dict[str, Segment]:
    """The segment of each severity word as the table draws it, on rows away from the cursor."""
    table = app.main.table
    found: dict[str, Segment] = {}
    for y in range(1, table.size.height):
        if int(table.scroll_y) + y - 1 == table.cursor_row:
            continue
        for segment in table.render_line(y):  # a word may share its segment with cells of its style
            for word in WORDS:
                if f" {word} " in f" {segment.text} " and word not in found:
                    found[word] = segment
    return found


def brightness(segment: Segment, default: str) -> float:
    color = segment.style.color if segment.style and segment.style.color else None
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
            assert cells[word].style.bold, f"{word} is drawn bold"
        assert not cells["INFO"].style.bold and not cells["DEBUG"].style.bold
        # A 16-colour terminal gets WARN and ERROR in different colours (they were both red).
        standard = {word: cells[word].style.color.downgrade(ColorSystem.STANDARD).number for word in ("WARN", "ERROR")}
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
        error, fatal, warn = cells["ERROR"].style, cells["FATAL"].style, cells["WARN"].style
        assert warn.bold and error.bold and error.underline and fatal.bold and fatal.reverse
        status = app.main.status_bar.content
        error_count = next(span for span in status.spans if status.plain[span.start : span.end].startswith("E"))
        style = error_count.style
        assert style.bold and style.color is not None and Color.parse(style.color.triplet.hex).brightness > 0.6, (
            "the E count stands out on the status line"
        )
