"""The status line in a given width: the least important parts give way first, each shortened,
then left out, before a more important one; the room that makes given back to the most
important."""

from __future__ import annotations

from rich.text import Text

from console_tui.ui.widgets.status_fit import COUNTS, DETAIL, SOURCE, STATE, Part, fit


def parts() -> list[Part]:
    return [
        Part(Text(" FOLLOW "), STATE, gap=""),
        Part(Text("40/40 shown"), COUNTS, Text("40/40")),
        Part(Text("/rosout_agg 5 pubs"), SOURCE, Text("/rosout_agg 5p")),
        Part(Text("tcpros"), DETAIL),
        Part(Text("a very long problem that never goes"), STATE, Text("a problem")),
    ]


def test_everything_in_full_when_it_fits():
    full = " FOLLOW   40/40 shown  /rosout_agg 5 pubs  tcpros  a very long problem that never goes"
    assert fit(parts(), None).plain == full
    assert fit(parts(), len(full)).plain == full


def test_the_least_important_shortened_then_left_out_first():
    # tcpros, the least important, has no short form: it goes, and the rest fits in full.
    assert fit(parts(), 80).plain == " FOLLOW   40/40 shown  /rosout_agg 5 pubs  a very long problem that never goes"
    assert fit(parts(), 75).plain == " FOLLOW   40/40  /rosout_agg 5 pubs  a very long problem that never goes"
    assert fit(parts(), 70).plain == " FOLLOW   /rosout_agg 5 pubs  a very long problem that never goes"
    # The problem is shortened at most; what that leaves gives the topic its full form back.
    assert fit(parts(), 40).plain == " FOLLOW   /rosout_agg 5 pubs  a problem"
    assert fit(parts(), 36).plain == " FOLLOW   /rosout_agg 5p  a problem"
    assert fit(parts(), 5).plain == " FOLLOW   a problem"  # the state and a problem never go
