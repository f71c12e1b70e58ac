"""Rule kinds and rqt_console's semantics, record by record (no ROS, no UI)."""

from itertools import product

import pytest

from console_tui.model.rules import (
    CustomRule,
    Entry,
    LocationRule,
    MessageRule,
    NodeRule,
    Role,
    RuleError,
    RuleSet,
    SeverityRule,
    TimeRangeRule,
    exclude,
    highlight,
)
from console_tui.model.rules.pattern_match import RequiredLiteral, required_literal
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record import LogRecord

S = 1_000_000_000


def rec(
    msg="Planner failed: goal unreachable",
    level=30,
    node="nav.planner",
    file="/ws/src/planner.cpp",
    function="make_plan",
    line=120,
    stamp_ns=100 * S,
):
    return LogRecord(stamp_ns=stamp_ns, level=level, node=node, msg=msg, file=file, function=function, line=line)


# -- message ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("rule", "msg", "hit"),
    [
        (MessageRule("failed"), "Planner failed", True),
        (MessageRule("FAILED"), "Planner failed", False),
        (MessageRule("FAILED", ignore_case=True), "Planner failed", True),
        (MessageRule("time(out|d out)", regex=True), "request timed out", True),
        (MessageRule("TIME(OUT|D OUT)", regex=True), "request timeout", False),
        (MessageRule("TIME(OUT|D OUT)", regex=True, ignore_case=True), "request timeout", True),
        (MessageRule("^goal", regex=True), "goal reached", True),
        (MessageRule("^goal", regex=True), "new goal", False),
        (MessageRule("reached$", regex=True), "goal reached", True),
        # non-ASCII: case folding is Unicode's (ß = ss), on the fast and the slow path alike
        (MessageRule("größe", ignore_case=True), "Falsche GRÖSSE", True),
        (MessageRule("ГРУЗ", ignore_case=True), "груз потерян", True),
        (MessageRule("груз"), "ГРУЗ", False),
        (MessageRule("😀"), "ok 😀", True),
        (MessageRule("x"), "", False),
        (MessageRule("a\nb"), "a\nb", True),
    ],
)
def test_message_rule(rule, msg, hit):
    assert rule.matches(rec(msg=msg)) is hit


def test_empty_inputs_match_nothing():
    record = rec()
    for rule in (
        MessageRule(""),
        MessageRule("", regex=True),
        SeverityRule(),
        NodeRule(()),
        NodeRule(("  ",)),
        LocationRule(),
        TimeRangeRule(),
        CustomRule(()),
        CustomRule((MessageRule(""), NodeRule(()))),
    ):
        assert rule.is_empty and not rule.matches(record), rule


def test_caseless_fast_path_over_many_messages():
    """Case folding string by string over whole chunks, separators and empty strings included."""
    store = LogStore()
    msgs = ["abc", "xABCx", "", "ab", "c abc abc", "\x00abc", "nothing", "ABC"] * 700
    store.extend_records(LogRecord(stamp_ns=0, level=20, node="n", msg=m) for m in msgs)
    test = MessageRule("abc", ignore_case=True).compile(store)
    got = b"".join(test(span.chunk, span.lo, span.hi) for span in store.spans(0, len(msgs)))
    assert list(got) == [int("abc" in m.casefold()) for m in msgs]


@pytest.mark.parametrize("pattern", ["a(", "[z-a]", "*x", "(?P<1>x)"])
def test_invalid_regex_names_problem_and_position(pattern):
    with pytest.raises(RuleError) as caught:
        MessageRule(pattern, regex=True)
    assert "invalid regular expression" in str(caught.value) and repr(pattern) in str(caught.value)
    assert caught.value.position is not None


def test_invalid_regex_in_location():
    with pytest.raises(RuleError, match="invalid regular expression"):
        LocationRule(function="(", regex=True)


# -- severity --------------------------------------------------------------------------------


def test_severity_rule():
    rule = SeverityRule.of("warn", "error")
    assert [rule.matches(rec(level=lv)) for lv in (10, 20, 30, 40, 50)] == [False, False, True, True, False]
    assert rule.matches(rec(level=35))  # between steps: counts as WARN
    assert SeverityRule.at_least(30).levels == {30, 40, 50}
    assert SeverityRule.at_most(20).levels == {10, 20}
    with pytest.raises(RuleError):
        SeverityRule(frozenset({7}))
    with pytest.raises(ValueError, match="unknown level"):
        SeverityRule.of("warm")


# -- node ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("names", "node", "hit"),
    [
        (("nav.planner",), "nav.planner", True),
        (("nav",), "nav.planner", False),  # exact, not prefix
        (("nav*",), "nav.planner", True),
        (("*planner",), "nav.planner", True),
        (("Nav*",), "nav.planner", False),  # case-sensitive, like ROS names
        (("nav.?lanner",), "nav.planner", True),
        (("[mn]av*",), "mav.x", True),
        (("/nav/planner",), "nav.planner", True),  # node name -> logger name
        (("/nav/*",), "nav.planner", True),
        (("rviz*", "nav*"), "nav.planner", True),
        (("ロボット",), "ロボット", True),
    ],
)
def test_node_rule(names, node, hit):
    assert NodeRule(names).matches(rec(node=node)) is hit


def test_node_lookup_grows_with_the_string_table():
    store = LogStore()
    test = NodeRule(("b*",)).compile(store)
    for batch in (["a", "b1"], ["c", "b2", "a"], [f"x{i}" for i in range(300)] + ["b3"]):
        start = store.end_seq
        store.extend_records(LogRecord(stamp_ns=0, level=20, node=n, msg="") for n in batch)
        got = b"".join(test(s.chunk, s.lo, s.hi) for s in store.spans(start, store.end_seq))
        assert list(got) == [int(n.startswith("b")) for n in batch]


# -- location --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("rule", "hit"),
    [
        (LocationRule(file="planner.cpp"), True),
        (LocationRule(file="PLANNER.CPP"), False),
        (LocationRule(file="PLANNER.CPP", ignore_case=True), True),
        (LocationRule(function="make_"), True),
        (LocationRule(line=120), True),
        (LocationRule(line=121), False),
        (LocationRule(file="planner.cpp", function="make_plan", line=120), True),
        (LocationRule(file="planner.cpp", line=7), False),
        (LocationRule(file=r"plan\w+\.cpp$", regex=True), True),
        (LocationRule(function="^plan", regex=True), False),
    ],
)
def test_location_rule(rule, hit):
    assert rule.matches(rec()) is hit


# -- time range ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("start", "end", "stamp", "hit"),
    [
        (10, 20, 10, True),  # both ends included
        (10, 20, 20, True),
        (10, 20, 21, False),
        (10, None, 10**12, True),  # open end
        (10, None, 9, False),
        (None, 20, -5, True),  # open start
        (None, 20, 21, False),
    ],
)
def test_time_range_rule(start, end, stamp, hit):
    assert TimeRangeRule(start, end).matches(rec(stamp_ns=stamp)) is hit


def test_time_range_start_after_end():
    with pytest.raises(RuleError, match="start is after the end"):
        TimeRangeRule(20, 10)


# -- custom ----------------------------------------------------------------------------------


def test_custom_rule_ands_its_non_empty_parts():
    parts = (SeverityRule.of("warn"), NodeRule(("nav*",)), MessageRule(""))
    assert CustomRule(parts).matches(rec())
    assert not CustomRule(parts).matches(rec(level=40))
    assert not CustomRule(parts).matches(rec(node="rviz"))
    assert CustomRule((MessageRule(""), LocationRule(line=120), TimeRangeRule(None, 200 * S))).matches(rec())
    with pytest.raises(RuleError):
        CustomRule((CustomRule(()),))


# -- semantics -------------------------------------------------------------------------------

WARN = SeverityRule.of("warn")  # matches rec()
NAV = NodeRule(("nav*",))  # matches rec()
RVIZ = NodeRule(("rviz*",))  # does not
EMPTY = MessageRule("")


def entries(*items):
    return RuleSet(tuple(items))


def test_no_rules_show_everything_plain():
    assert entries().verdict(rec()) == (True, None)
    assert entries().with_highlighted_only(True).verdict(rec()) == (True, None)


@pytest.mark.parametrize(
    ("excludes", "shown"),
    [
        ((exclude(WARN),), False),
        ((exclude(RVIZ),), True),
        ((exclude(RVIZ), exclude(NAV)), False),  # any exclude hides
        ((exclude(WARN, enabled=False),), True),  # disabled: ignored
        ((exclude(WARN, inverted=True),), True),  # inverted: matches what it does not
        ((exclude(RVIZ, inverted=True),), False),
        ((exclude(EMPTY),), True),  # empty: matches nothing
        ((exclude(EMPTY, inverted=True),), True),  # even inverted
    ],
)
def test_exclude_rules(excludes, shown):
    assert entries(*excludes).verdict(rec()) == (shown, None)


@pytest.mark.parametrize(
    ("highlights", "decoration"),
    [
        ((highlight(NAV),), "highlight"),
        ((highlight(RVIZ),), "dim"),
        ((highlight(RVIZ), highlight(NAV)), "highlight"),  # any highlight
        ((highlight(NAV, inverted=True),), "dim"),
        ((highlight(RVIZ, inverted=True),), "highlight"),
        ((highlight(NAV, enabled=False),), None),  # none active: nothing dimmed
        ((highlight(EMPTY),), None),
        ((highlight(EMPTY), highlight(RVIZ)), "dim"),
    ],
)
@pytest.mark.parametrize("highlighted_only", [False, True])
def test_highlight_rules_and_highlighted_only(highlights, decoration, highlighted_only):
    rules = entries(*highlights).with_highlighted_only(highlighted_only)
    shown = not (highlighted_only and decoration == "dim")
    assert rules.verdict(rec()) == (shown, decoration)


def test_every_combination_against_the_rule():
    """Exclude x highlight x enabled x inverted x highlighted-only, against the stated rule."""
    record = rec()
    for ex_rule, hl_rule, ex_on, hl_on, ex_inv, hl_inv, only in product(
        (WARN, RVIZ, EMPTY), (NAV, RVIZ, EMPTY), *([(False, True)] * 5)
    ):
        ex = Entry(ex_rule, Role.EXCLUDE, ex_on, ex_inv)
        hl = Entry(hl_rule, Role.HIGHLIGHT, hl_on, hl_inv)
        rules = RuleSet((ex, hl), only)

        def hits(entry):
            return entry.active and (entry.rule.matches(record) != entry.inverted)

        highlighting = hl.active
        highlighted = hits(hl) if highlighting else True
        shown = not hits(ex) and (not only or highlighted)
        decoration = ("highlight" if highlighted else "dim") if highlighting else None
        assert rules.verdict(record) == (shown, decoration), rules


def test_rule_set_edits_return_new_sets():
    rules = entries(exclude(WARN))
    edited = rules.with_rule(0, RVIZ).add(highlight(NAV)).with_inverted(1, True).with_role(0, Role.HIGHLIGHT)
    assert rules.entries == (exclude(WARN),)
    assert edited.entries == (highlight(RVIZ), highlight(NAV, inverted=True))
    assert edited.remove(0).entries == (highlight(NAV, inverted=True),)
    assert edited.with_enabled(1, False).entries[1].enabled is False
    assert not edited.filtering and edited.with_highlighted_only(True).filtering


def test_query_entries_replace_previous_query_entries():
    rules = entries(exclude(WARN)).with_query((highlight(NAV),))
    assert [e.from_query for e in rules.entries] == [False, True]
    again = rules.with_query((exclude(RVIZ),))
    assert [e.rule for e in again.entries] == [WARN, RVIZ]


def test_describe_is_readable():
    assert exclude(WARN, inverted=True).describe() == "not severity WARN"
    assert MessageRule("x", ignore_case=True).describe() == "message 'x' (ignore case)"
    assert CustomRule((WARN, NAV)).describe() == "severity WARN and node nav*"


@pytest.mark.parametrize(
    ("pattern", "ignore_case"),
    [
        ("time(out|d out)", True),
        (r"\d{3}\.\d ms", False),
        ("^goal", False),
        ("ab?c", True),
        ("K", True),
        ("s$", True),
        ("a|b", False),
        ("x\x00", False),
        ("(?i)ABC", False),
        # the search window around the literal: lookarounds, anchors, overlaps, unbounded parts
        (r"(?<=k )\d+\.\d ms", False),
        (r"\bms\b", False),
        (r" ms(?!x)", False),
        (r"\d ms$", False),
        ("aab", False),
        ("abab", True),
        (r"(\d)\1\d\.\d ms", False),
        (r"to.*ms", False),
        (r"o{2,3}k", True),
        (r"(bc|b)c?d", False),
        (r"\d{3}\.\d MS", True),
    ],
)
def test_regex_prefilter_agrees_with_plain_search(pattern, ignore_case):
    """The literal prefilter must never change a regex's answer (ASCII or not)."""
    import re

    msgs = [
        "timeout",
        "TIMED OUT",
        "took 123.4 ms",
        "goal",
        "a goal",
        "abc",
        "AC",
        "\u212a",
        "ſ",
        "bus",
        "x\x00y",
        "xabcx",
        "",
        "Größe",
        "ABC abc",
        "took 1.2 ms then 445.5 ms",
        "1.5 msx 22.3 ms",
        "aaab",
        "ababab",
        "xabab",
        "bcd bd",
        "TOOK 12.25 MS",
        "ms",
        " ms",
        "9 ms",
        "toOOk",
        "ook",
    ] * 300
    for chunk in (msgs, [m for m in msgs if m.isascii() and "\x00" not in m]):
        store = LogStore()
        store.extend_records(LogRecord(stamp_ns=0, level=20, node="n", msg=m) for m in chunk)
        test = MessageRule(pattern, ignore_case=ignore_case, regex=True).compile(store)
        got = b"".join(test(s.chunk, s.lo, s.hi) for s in store.spans(0, len(chunk)))
        search = re.compile(pattern, re.I if ignore_case else 0).search
        assert list(got) == [int(search(m) is not None) for m in chunk]


def test_custom_rule_narrowing_agrees_with_each_part():
    """Text parts are tested only on records the other parts let through: same answers."""
    records = [
        rec(level=10 * (1 + i % 5), node=f"n{i % 9}", msg=f"goal {i} {'x' * (i % 4)}", line=i % 11) for i in range(5000)
    ]
    store = LogStore()
    store.extend_records(records)
    for parts in (
        (SeverityRule.of("warn"), MessageRule("xx"), MessageRule("goal 1", regex=True)),
        (NodeRule(("n1",)), LocationRule(line=3), MessageRule("X", ignore_case=True)),
        (MessageRule("xxx"), MessageRule("9")),
        (SeverityRule.of("fatal"), NodeRule(("n2",)), MessageRule("goal")),
    ):
        rule = CustomRule(parts)
        test = rule.compile(store)
        got = b"".join(test(s.chunk, s.lo, s.hi) for s in store.spans(0, len(records)))
        wanted = [1] * len(records)
        for part in parts:
            part_test = part.compile(store)
            mask = b"".join(part_test(s.chunk, s.lo, s.hi) for s in store.spans(0, len(records)))
            wanted = [a & b for a, b in zip(wanted, mask, strict=False)]
        assert list(got) == wanted


@pytest.mark.parametrize(
    ("pattern", "expected"),
    [
        (r"\d{3}\.\d ms", RequiredLiteral(" ms", lead=5, tail=0, fixed_lead=True)),
        ("time(out|d out)", RequiredLiteral("time", lead=0, tail=5, fixed_lead=True)),
        ("^goal", RequiredLiteral("goal", lead=0, tail=None, fixed_lead=True)),  # an anchor: no end to the window
        (r"x.*abc", RequiredLiteral("abc", lead=None, tail=0)),
        (r"\d{1,3} ms", RequiredLiteral(" ms", lead=3, tail=0)),  # a lead of 1 to 3: not fixed
    ],
)
def test_required_literal_and_its_window(pattern, expected):
    import re

    assert required_literal(re.compile(pattern)) == expected
