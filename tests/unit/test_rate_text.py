"""The timeline's rates as people read them: per second, or per minute, hour or day when slow."""

import pytest

from console_tui.ui.widgets.timeline_drawing import rate_text


@pytest.mark.parametrize(
    ("rate", "text"),
    [
        (50_000, "50k/s"),
        (250, "250/s"),
        (0.5, "0.5/s"),
        (0.05, "3/min"),
        (0.001, "3.6/h"),
        (7.7e-07, "0.067/day"),  # a file spanning years: once said 7.7e-07/s
        (0, "0/s"),
    ],
)
def test_rates_read_as_people_say_them(rate, text):
    assert rate_text(rate) == text
