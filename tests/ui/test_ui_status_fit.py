"""The status line in a given width: the least important parts give way first, each shortened,
then left out, before a more important one; the room that makes given back to the most
important."""

from __future__ import annotations

from rich.text import Text

from console_tui.model.inert_text import one_line
from console_tui.sources.status import SourceStatus
from console_tui.ui.widgets.status_bar import StatusFacts, render_status, short_problem
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


def test_a_problem_in_a_narrow_line_says_what_is_wrong_not_where():
    # At 80 columns the ROS 1 status line showed "waiting for master at http://127.0.0.1:1",
    # cut in the address, which the line shows anyway (ROS 1 127.0.0.1:12399).
    waiting = "waiting for master at http://127.0.0.1:12399: connection refused (nothing listens there)"
    assert short_problem(waiting) == "waiting for master: connection refused …"
    assert short_problem("the master at http://robot:11311/: timed out") == "the master: timed out"
    assert short_problem("no \x1b[31mescape\x1b[0m at all") == one_line("no \x1b[31mescape\x1b[0m at all")
    master = SourceStatus(origin="ROS 1 http://127.0.0.1:12399/", problem=waiting)
    line = render_status(StatusFacts(sources=[master]), width=80).plain
    assert "waiting for master: connection refused …" in line
    assert "ROS 1 127.0.0.1:12399" in line
