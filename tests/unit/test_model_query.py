"""The query line: what each query compiles to, errors with positions, history."""

from datetime import datetime, timezone

import pytest

from console_tui.model.rules import (
    CustomRule,
    LocationRule,
    MessageRule,
    NodeRule,
    Role,
    RuleSet,
    SeverityRule,
    TimeRangeRule,
    exclude,
    highlight,
)
from console_tui.model.rules.history import QueryHistory
from console_tui.model.rules.query import QueryError, caret_line, parse_query
from console_tui.model.store.record import LogRecord

S = 1_000_000_000
NOW = int(datetime(2024, 5, 1, 12, 0, tzinfo=timezone.utc).timestamp()) * S


def q(text):
    return parse_query(text, now_ns=NOW, utc=True)


def only(*parts):
    """What unsigned terms compile to: exclude whatever does not match them all."""
    rule = parts[0] if len(parts) == 1 else CustomRule(parts)
    return exclude(rule, inverted=True)


def test_issue_example():
    entries = q('level>=warn node:nav* -node:rviz* "planner failed" /time(out|d out)/i file:planner.cpp')
    assert entries == (
        only(
            SeverityRule.of("warn", "error", "fatal"),
            NodeRule(("nav*",)),
            MessageRule("planner failed", ignore_case=True),
            MessageRule("time(out|d out)", ignore_case=True, regex=True),
            LocationRule(file="planner.cpp", ignore_case=True),
        ),
        exclude(NodeRule(("rviz*",))),
    )


@pytest.mark.parametrize(
    ("text", "entries"),
    [
        ("", ()),
        ("   ", ()),
        ("timeout", (only(MessageRule("timeout", ignore_case=True)),)),
        ("Timeout", (only(MessageRule("Timeout")),)),  # smart case
        ('"Größe falsch"', (only(MessageRule("Größe falsch")),)),
        ('"say \\"hi\\""', (only(MessageRule('say "hi"', ignore_case=True)),)),
        ("/a\\/b/", (only(MessageRule("a/b", regex=True)),)),
        ("/\\d+ ms/", (only(MessageRule("\\d+ ms", regex=True)),)),
        ("msg:/x/i", (only(MessageRule("x", ignore_case=True, regex=True)),)),
        ("level:error,fatal", (only(SeverityRule.of("error", "fatal")),)),
        ("level=warn", (only(SeverityRule.of("warn")),)),
        ("severity>info", (only(SeverityRule.of("warn", "error", "fatal")),)),
        ("level<warn", (only(SeverityRule.of("debug", "info")),)),
        ("level<=WARNING", (only(SeverityRule.of("debug", "info", "warn")),)),
        ("-level:debug", (exclude(SeverityRule.of("debug")),)),
        ("+node:nav*,/ns/x", (highlight(NodeRule(("nav*", "/ns/x"))),)),
        ("node:/talker", (only(NodeRule(("/talker",))),)),  # a ROS (1) node name, not a regex
        ("-node:/ns/*,/rosout", (exclude(NodeRule(("/ns/*", "/rosout"))),)),
        ("+error +node:a", (highlight(MessageRule("error", ignore_case=True)), highlight(NodeRule(("a",))))),
        ("-(node:a level:info)", (exclude(CustomRule((NodeRule(("a",)), SeverityRule.of("info")))),)),
        (
            "+( func:/^on_/ line:7 )",
            (highlight(CustomRule((LocationRule(function="^on_", regex=True), LocationRule(line=7)))),),
        ),
        ("file:Planner.cpp", (only(LocationRule(file="Planner.cpp")),)),
        ("since:10:30", (only(TimeRangeRule(NOW - 90 * 60 * S)),)),
        ("until:5m", (only(TimeRangeRule(None, NOW - 300 * S)),)),
        ("time:1714564800.5..", (only(TimeRangeRule(NOW + S // 2)),)),
        ("time:..2024-05-01T12:00:00", (only(TimeRangeRule(None, NOW)),)),
        ("time:2024-05-01..11:59:59.25", (only(TimeRangeRule(NOW - 12 * 3600 * S, NOW - 750_000_000)),)),
        ("http://x/y", (only(MessageRule("http://x/y", ignore_case=True)),)),
        ("12:30", (only(MessageRule("12:30", ignore_case=True)),)),
    ],
)
def test_queries(text, entries):
    assert q(text) == entries


@pytest.mark.parametrize(
    ("text", "position", "reason"),
    [
        ('"open', 0, "unterminated quote"),
        ("x /ab", 2, "unterminated regular expression"),
        ("/a(/", 2, "missing ), unterminated subpattern"),
        ("ok /[z-a]/", 5, "bad character range"),
        ("/x/g", 3, "unknown regular expression flags"),
        ("nod:x", 0, "unknown key 'nod'"),
        ("level:warm", 6, "unknown level 'warm'"),
        ("level:warn,bogus", 11, "unknown level 'bogus'"),
        ("level>fatal", 6, "matches no severity"),
        ("level>=warn,error", 7, "takes one level"),
        ("node>=x", 0, "only works with level"),
        ("line:abc", 5, "expected a line number"),
        ("since:yesterday", 6, "not a time"),
        ("time:5", 5, "expected FROM..TO"),
        ("time:..", 5, "at least one end"),
        ("time:2024-05-02..2024-05-01", 5, "start is after the end"),
        ("a -", 2, "expected a term after '-'"),
        ("(a b", 0, "unclosed '('"),
        ("a )", 2, "unexpected ')'"),
        ("+(a -b)", 4, "cannot be used inside a group"),
        ("-()", 1, "empty group"),
        ("node:", 5, "needs a value"),
    ],
)
def test_errors_name_problem_and_position(text, position, reason):
    with pytest.raises(QueryError) as caught:
        q(text)
    assert caught.value.position == position
    assert reason in caught.value.reason
    assert caret_line(text, caught.value).splitlines()[1].index("^") == position


def test_query_rules_behave_like_the_issue_says():
    rules = RuleSet().with_query(q('level>=warn -node:rviz* +"planner failed"'))

    def rec(level, node, msg):
        return LogRecord(stamp_ns=0, level=level, node=node, msg=msg)

    assert rules.verdict(rec(30, "nav", "Planner failed: x")) == (True, "highlight")
    assert rules.verdict(rec(40, "nav", "ok")) == (True, "dim")
    assert rules.verdict(rec(20, "nav", "planner failed"))[0] is False
    assert rules.verdict(rec(50, "rviz2", "planner failed"))[0] is False
    assert all(entry.from_query for entry in rules.entries)
    assert [e.role for e in rules.entries] == [Role.EXCLUDE, Role.EXCLUDE, Role.HIGHLIGHT]


def test_history_walks_back_and_forth_and_keeps_the_draft(tmp_path):
    history = QueryHistory(limit=3)
    for text in ("a", "b", "a", "", "c", "d"):
        history.add(text)
    assert history.items == ["a", "c", "d"]
    assert history.previous("draft") == "d"
    assert history.previous("ignored") == "c"
    assert history.previous("") == "a"
    assert history.previous("") is None
    assert history.following() == "c"
    assert history.following() == "d"
    assert history.following() == "draft"
    assert history.following() is None
    path = tmp_path / "sub" / "history.txt"
    history.save(path)
    assert QueryHistory.load(path).items == ["a", "c", "d"]
    assert QueryHistory.load(tmp_path / "missing").items == []
    assert QueryHistory().previous("x") is None


def test_ros1_node_names_on_the_query_line():
    """ROS 1 loggers are node names (``/talker``): ``node:/talker`` names one, as does a
    glob over a namespace; the ROS 2 logger of the same node (``talker``) matches too."""
    rules = RuleSet().with_query(q("node:/talker,/ns/*"))

    def shown(node: str) -> bool:
        return rules.verdict(LogRecord(stamp_ns=0, level=20, node=node, msg="m"))[0]

    assert [shown(n) for n in ("/talker", "talker", "/ns/cam", "ns.cam", "/other", "/talker2")] == [
        True,
        True,
        True,
        True,
        False,
        False,
    ]
