"""Fitting the status line into the terminal's width: each part has a priority and, often, a
short form. When the line is too long, parts are taken in turn, the least important first:
each is shortened when it has a short form (a part is always shortened before it goes), else
left out. When every short form is not enough, the shortened parts go too, the least
important first; and the room that leaves gives the most important parts their full forms
back. The state (FOLLOW, PAUSED) and a source's problem never go.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from rich.text import Text

#: Priorities, most important first.
STATE, SOURCE, WHERE, COUNTS, DEMO, RATE, DETAIL = range(7)


@dataclass
class Part:
    """One part of the status line: its text, a shorter one (or None), how much it matters
    (``STATE`` most), and the gap before it."""

    text: Text
    priority: int
    short: Text | None = None
    gap: str = "  "

    def width(self, short: bool) -> int:
        text = self.short if short and self.short is not None else self.text
        return len(self.gap) + text.cell_len


def fit(parts: Sequence[Part], width: int | None) -> Text:
    """The parts in their order, in ``width`` cells (None: all of them, in full)."""
    shortened = [False] * len(parts)
    kept = [True] * len(parts)
    if width is not None:
        total = sum(part.width(False) for part in parts)
        # The least important first; among equals, the rightmost first.
        order = sorted(range(len(parts)), key=lambda i: (-parts[i].priority, -i))
        for i in order:  # each part shortened if it can be, else left out (the state never)
            if total <= width:
                break
            if parts[i].short is not None:
                total -= parts[i].width(False) - parts[i].width(True)
                shortened[i] = True
            elif parts[i].priority > STATE:
                total -= parts[i].width(False)
                kept[i] = False
        for i in order:  # still too long: shortened parts go too
            if total <= width:
                break
            if kept[i] and parts[i].priority > STATE:
                total -= parts[i].width(shortened[i])
                kept[i] = False
        for i in reversed(order):  # room made by leaving parts out: the most important in full again
            if kept[i] and shortened[i]:
                longer = parts[i].width(False) - parts[i].width(True)
                if total + longer <= width:
                    total += longer
                    shortened[i] = False
    line = Text(no_wrap=True, overflow="ellipsis")
    first = True
    for part, short, keep in zip(parts, shortened, kept, strict=True):
        if not keep:
            continue
        if not first:
            line.append(part.gap)
        first = False
        line.append_text(part.short if short and part.short is not None else part.text)
    return line
