"""The rules in SQL against the model's own rules, on the same records in the real engine:
what SQL is sure of the rule matches, what the rule matches SQL may keep, and a window asked
with the rules pushed down shows exactly what the rules show over everything."""

from __future__ import annotations

import random

import pytest

from console_tui.model.rules.query import parse_query
from console_tui.model.rules.ruleset import Role, RuleSet
from console_tui.model.rules.stream import StreamFilter
from console_tui.model.store.record import LogRecord
from console_tui.warehouse.pages import TablePages
from console_tui.warehouse.pushdown import condition, exact, re2_pattern, where

from support.warehouse import chdb_address, needs_store, rows_of, ship_records, table_client

pytestmark = needs_store

T0 = 1_765_000_000_000_000_000
NODES = ["nav.planner", "nav.controller", "/talker", "ns.talker", "cam_driver", "x%y_z"]
ROBOTS = ["", "picker", "cart", "arm2"]
TEXTS = [
    "planner failed to find a path",
    "Planner FAILED",
    "path found in 0.2 s",
    "Größe überschritten",
    "İstanbul kelvin \u212a",
    "a.b and a\nb",
    "line ends x\n",
    "ﬁle not found",
    "timeout (5 s)",
    "[warn] bracket",
    "100% done",
    "",
]
TERMS = [
    "level>=warn",
    "level<info",
    "level:info,error",
    "level>error",
    "node:nav*",
    "node:/talker",
    "node:ns.talk?r",
    "node:picker:/talker",
    "node:arm*:nav*",
    "node:x%y_z",
    "node:[nc]*",
    "robot:pick*",
    "robot:cart,arm2",
    "planner",
    "Planner",
    '"FAILED"',
    "größe",
    "istanbul",
    "k",
    "/plan.er/",
    "/PLAN/i",
    "/a.b/",
    "/x$/",
    "/^pa/",
    "/(fail|found)/",
    "/[0-9]+ s/",
    "/\\d/",
    "/a{2,}/",
    "/\\(5 s\\)/",
    "/[[:alpha:]]/",
    "/file/i",
    "file:file1",
    "file:/FILE[01]/i",
    "func:/^pl/",
    "line:12",
    f"since:{(T0 + 400_000_000) / 1e9:.1f}",
    f"until:{(T0 + 700_000_000) / 1e9:.1f}",
    f"time:{(T0 + 100_000_000) / 1e9:.1f}..{(T0 + 200_000_000) / 1e9:.1f}",
]


def test_regexes_go_down_only_where_python_and_re2_agree():
    assert re2_pattern("plan.er", False) == "(?-s)plan.er"
    assert re2_pattern("(?:a|b)+c", True) == "(?i)(?-s)(?:a|b)+c"
    for pattern in ["x$", "\\d+", "(?=a)", "(a)\\1", "[[:alpha:]]", "a*+", "a{,3}", "é", "\\bword"]:
        assert re2_pattern(pattern, False) is None, pattern


def corpus(count: int = 900) -> list[LogRecord]:
    pick = random.Random(7)
    return [
        LogRecord(
            T0 + i * 1_000_000,
            pick.choice([10, 20, 25, 30, 40, 50, 55]),
            pick.choice(NODES),
            pick.choice(TEXTS) + pick.choice(["", " #12", " retry"]),
            pick.choice(["/src/file0.cpp", "/src/FILE1.py", ""]),
            pick.choice(["plan", "update", ""]),
            pick.choice([0, 12, 120]),
            robot=pick.choice(ROBOTS),
        )
        for i in range(count)
    ]


def stamps_where(client, sql: str) -> set[int]:
    columns = client.columns(f"SELECT toUnixTimestamp64Nano(Timestamp) FROM {client.table} WHERE {sql}")
    return set(columns[0]) if columns else set()


@pytest.fixture
def shipped(tmp_path):
    address = chdb_address(tmp_path)
    records = corpus()
    ship_records(address, records, host="")
    with table_client(address) as client:
        yield records, client


def test_each_rule_sure_within_what_it_matches_within_maybe(shipped):
    records, client = shipped
    for term in TERMS:
        for entry in parse_query(f"-({term})" if " " in term else f"-{term}"):
            rule = entry.rule
            matched = {r.stamp_ns for r in records if rule.matches(r)}
            found = condition(rule)
            sure, maybe = stamps_where(client, found.sure), stamps_where(client, found.maybe)
            assert sure <= matched <= maybe, term
            if found.exact:
                assert sure == matched, term


def random_rules(pick: random.Random) -> RuleSet:
    parts = []
    for _ in range(pick.randint(1, 4)):
        term = pick.choice(TERMS)
        parts.append(pick.choice(["", "", "-", "+"]) + term)
    rules = RuleSet().with_query(parse_query(" ".join(parts)))
    return rules.with_highlighted_only(pick.random() < 0.3)


def test_a_window_asked_with_the_rules_shows_what_the_rules_show(shipped):
    _, client = shipped
    records = TablePages(client).newest(10_000).records()  # as the console reads them
    pick = random.Random(11)
    exact_sets = 0
    for _ in range(120):
        rules = random_rules(pick)
        expected = [record for record, _ in StreamFilter(rules).filter(records)]
        sent = TablePages(client, where(rules)).newest(10_000).records()
        shown = [record for record, _ in StreamFilter(rules).filter(sent)]
        assert rows_of(shown) == rows_of(expected), rules
        if exact(rules):
            exact_sets += 1
            assert rows_of(sent) == rows_of(expected), rules
        if rules.active(Role.EXCLUDE) and exact(rules):
            assert len(sent) <= len(records)
    assert exact_sets > 20  # most rule sets go down whole
