"""Fitting the status line into the terminal's width: each part has a priority and, often, a
short form. When the line is too long, parts give way in turn, the least important first:
each is shortened when it has a short form, and left out when that is not enough, before a
more important part is touched. What room is left then (a more important part shortened
late, or left out) takes parts back and gives them their full forms, the most important
first; a part that does not fit in it leaves the room to the next. The state (FOLLOW,
PAUSED) and a source's problem are shortened at most, never left out.
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
        for i in order:  # each part shortened first, then left out, before a more important one
            if total > width and parts[i].short is not None:
                total -= parts[i].width(False) - parts[i].width(True)
                shortened[i] = True
            if total > width and parts[i].priority > STATE:
                total -= parts[i].width(shortened[i])
                kept[i] = False
        for i in reversed(order):  # room left: parts back in full, the most important first
            part = parts[i]
            if kept[i] and shortened[i]:
                if total + part.width(False) - part.width(True) <= width:
                    total += part.width(False) - part.width(True)
                    shortened[i] = False
            elif not kept[i]:
                # A part too wide for the room leaves it to the less important ones after it
                # (a long command's words must not leave the counts out of a wide line).
                short = part.short is not None and total + part.width(False) > width
                if total + part.width(short) <= width:
                    total += part.width(short)
                    kept[i], shortened[i] = True, short
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
