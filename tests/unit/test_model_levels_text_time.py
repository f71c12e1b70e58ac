"""Levels, inert text and time formatting."""

import pytest

from console_tui.model import inert_text, levels, timefmt
from console_tui.model.levels import Severity


@pytest.mark.parametrize(
    "name,expected",
    [("debug", 10), ("INFO", 20), ("Warn", 30), ("warning", 30), ("error", 40), ("FATAL", 50), ("30", 30)],
)
def test_parse_severity(name, expected):
    assert levels.parse_severity(name) == expected


@pytest.mark.parametrize("bad", ["loud", "", "15", "unset"])
def test_parse_severity_rejects_with_names(bad):
    with pytest.raises(ValueError, match="debug, info, warn, error, fatal"):
        levels.parse_severity(bad)


def test_unset_only_when_allowed():
    assert levels.parse_severity("unset", allow_unset=True) is Severity.UNSET


def test_ros1_mapping_both_ways():
    assert [levels.from_ros1(v) for v in (1, 2, 4, 8, 16)] == [10, 20, 30, 40, 50]
    assert [levels.to_ros1(v) for v in (10, 20, 30, 40, 50)] == [1, 2, 4, 8, 16]
    assert levels.from_ros1(0) == 10 and levels.from_ros1(12) == 40


@pytest.mark.parametrize(
    "level, ros1",
    [
        *[(0, 1), (5, 1), (10, 1), (15, 1), (19, 1), (20, 2), (25, 2), (29, 2), (30, 4)],
        *[(35, 4), (39, 4), (40, 8), (45, 8), (49, 8), (50, 16), (55, 16), (255, 16)],
    ],
)
def test_to_ros1_rounds_levels_between_steps_down(level, ros1):
    assert levels.to_ros1(level) == ros1
    assert levels.from_ros1(ros1) == levels.severity_bucket(level), "the step below, as severity rules count it"


def test_ros1_levels_beyond_the_bits_and_parse_errors_list_the_names():
    assert levels.from_ros1(32) == 50 and levels.from_ros1(1 << 20) == 50, "above FATAL: FATAL"
    assert levels.from_ros1(3) == 20 and levels.from_ros1(-4) == 10
    with pytest.raises(ValueError) as error:
        levels.parse_severity("warm", allow_unset=True)
    assert str(error.value) == "unknown level 'warm': use one of debug, info, warn, error, fatal, unset"
    with pytest.raises(ValueError) as error:
        levels.parse_severity("15")
    assert str(error.value) == "unknown level '15': use one of debug, info, warn, error, fatal"


def test_severity_names():
    assert levels.severity_name(30) == "WARN"
    assert levels.severity_name(33) == "33"
    assert levels.severity_bucket(33) == Severity.WARN


def test_one_line_makes_controls_visible():
    hostile = "a\x1b[31mred\x1b]0;title\x07\x00b\nc\td\u202eevil\x9b"
    out = inert_text.one_line(hostile)
    assert "\x1b" not in out and "\x00" not in out and "\n" not in out and "\u202e" not in out
    assert "\x9b" not in out and "\x07" not in out
    assert out.startswith("a\u241b[31mred")
    assert "<U+202E>" in out


@pytest.mark.parametrize(
    "char", ["\u200b", "\u2028", "\u2029", "\u2060", "\ufeff", "\u00ad", "\u180e", "\U000e0041", "\u3164"]
)
def test_invisible_and_line_breaking_characters_show_as_stand_ins(char):
    for render in (inert_text.one_line, inert_text.multi_line):
        out = render(f"a{char}b")
        assert out == f"a<U+{ord(char):04X}>b" and char not in out


def test_joiners_that_text_needs_are_kept():
    family = "\U0001f469\u200d\U0001f469\u200d\U0001f467 \u0645\u200c\u06cc \u2764\ufe0f"
    assert inert_text.one_line(family) == family


def test_one_line_cuts_before_work():
    assert len(inert_text.one_line("x" * 1_000_000, limit=50)) == 50


def test_multi_line_keeps_newlines_and_cjk():
    out = inert_text.multi_line("漢字 🚀 שלום\r\nline2\x1b[0m")
    assert out == "漢字 🚀 שלום\nline2\u241b[0m"


def test_surrogates_become_replacement():
    assert inert_text.one_line("bad\udcff") == "bad\ufffd"


def test_first_line():
    assert inert_text.first_line("one\ntwo", 100) == ("one", True)
    assert inert_text.first_line("abcdef", 3) == ("abc", True)
    assert inert_text.first_line("abc", 3) == ("abc", False)


def test_stamp_text_pads_nanoseconds():
    assert timefmt.stamp_text(1_700_000_000_000_000_042) == "1700000000.000000042"


def test_clock_text_utc():
    assert timefmt.clock_text(1_700_000_000_123_456_789, utc=True) == "22:13:20.123"
    assert timefmt.full_text(1_700_000_000_123_456_789, utc=True) == "2023-11-14 22:13:20.123456789 +0000"


@pytest.mark.parametrize(
    ("count", "words", "expected"),
    [
        (0, ("line",), "0 lines"),
        (1, ("line",), "1 line"),
        (2, ("line",), "2 lines"),
        (1200, ("record",), "1,200 records"),
        (1, ("entry", "entries"), "1 entry"),
        (3, ("entry", "entries"), "3 entries"),
    ],
)
def test_plural_agrees_with_the_count(count, words, expected):
    assert inert_text.plural(count, *words) == expected


@pytest.mark.parametrize(
    ("name", "width", "shown"),
    [
        ("talker", 16, "talker"),
        ("sensors.lidar_driver", 20, "sensors.lidar_driver"),
        ("sensors.lidar_driver", 16, "s.lidar_driver"),
        ("navigation.planner.costmap", 20, "n.planner.costmap"),
        ("navigation.planner.costmap", 12, "n.p.costmap"),
        ("navigation.planner", 12, "n.planner"),
        ("power.battery_monitor", 15, "p.ba…ry_monitor"),
        ("a_very_long_node_name_without_dots", 10, "a_v…t_dots"),
    ],
)
def test_shorten_name_keeps_the_distinguishing_end(name, width, shown):
    assert inert_text.shorten_name(name, width) == shown
    assert len(inert_text.shorten_name(name, width)) <= width
