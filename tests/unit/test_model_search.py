"""Search and jumps in the model: every match found from an anchor outwards, in steps,
agreeing with a plain test of every shown record; packed and unpacked chunks; rules;
eviction and arrivals; a catastrophic regex abandoned."""

from __future__ import annotations

import random

import pytest

from console_tui.model.levels import Severity
from console_tui.model.rules.message import MessageRule
from console_tui.model.rules.rule import RuleError
from console_tui.model.rules.ruleset import RuleSet, exclude
from console_tui.model.rules.severity import SeverityRule
from console_tui.model.store.log_store import CHUNK_SIZE, LogStore
from console_tui.model.store.packed_texts import PackedTexts
from console_tui.model.store.record import LogRecord
from console_tui.model.view.log_view import LogView
from console_tui.model.view.search_walk import PENDING, Search, must_hold, parse_search, text_hits
from console_tui.model.view.seek import Seeker, level_hits, view_shows

from support.clock import TickingClock

WORDS = ["Timeout waiting", "timed out", "goal reached", "Größe 3", "ok", "scan done", "TIMEOUT"]


def make_store(count: int, seed: int = 1, max_messages: int = 1_000_000, words=WORDS) -> LogStore:
    rng = random.Random(seed)
    store = LogStore(max_messages=max_messages)
    store.extend_records(
        LogRecord(stamp_ns=i, level=rng.choice([10, 20, 20, 30, 40]), node="n", msg=f"{rng.choice(words)} {i}")
        for i in range(count)
    )
    return store


def finish(view: LogView) -> None:
    while view.refiltering:
        view.refilter_step(1.0)


def brute(view: LogView, text: str) -> list[int]:
    match = parse_search(text)
    predicate = match.predicate()
    return [view.seq_at(row) for row in range(len(view)) if predicate(view.store.get(view.seq_at(row)).msg)]


def run(search: Search, prefer: int = 0) -> None:
    for _ in range(10_000):
        if search.step(0.5, prefer):
            return
    raise AssertionError("search never completed")


def test_parse_search_smart_case_and_regex():
    assert parse_search("timeout") == parse_search(" timeout ")
    assert parse_search("timeout").ignore_case and not parse_search("Timeout").ignore_case
    assert parse_search("/time(out)/").regex and not parse_search("/time(out)/").ignore_case
    assert parse_search("/time(out)/i").ignore_case
    assert parse_search("/").text == "/" and not parse_search("/").regex
    with pytest.raises(RuleError):
        parse_search("/a(/")


@pytest.mark.parametrize("text", ["timeout", "Timeout", "größe", "/time(out|d out)/i", "/^goal/", "/\\d+$/", "zzz"])
@pytest.mark.parametrize("filtered", [False, True])
def test_search_finds_what_a_plain_test_finds(text, filtered):
    store = make_store(3 * CHUNK_SIZE + 500)  # three packed chunks and a growing one
    view = LogView(store)
    if filtered:
        view.set_rules(RuleSet((exclude(SeverityRule.of("debug")),)))
        finish(view)
    anchor = view.seq_at(len(view) // 2)
    search = Search(view, parse_search(text), anchor)
    run(search)
    expected = brute(view, text)
    assert list(search.seqs()) == expected
    assert search.count() == len(expected)
    if expected:
        middle = expected[len(expected) // 2]
        assert search.index(middle) == len(expected) // 2 + 1
        assert search.nearest(middle, forward=True) == (expected[len(expected) // 2 + 1] if len(expected) > 1 else None)
        assert search.nearest(middle, forward=True, inclusive=True) == middle
        assert search.nearest(expected[0], forward=False) is None
        assert search.nearest(expected[-1], forward=True) is None


def test_the_nearest_match_is_known_before_the_search_completes():
    store = make_store(10 * CHUNK_SIZE)
    store.extend_records([LogRecord(stamp_ns=0, level=20, node="n", msg="the needle")])
    store.extend_records(LogRecord(stamp_ns=0, level=20, node="n", msg="hay") for _ in range(CHUNK_SIZE))
    view = LogView(store)
    view.clock = TickingClock(0.001)  # a step of 1 ms walks one piece, on any machine
    search = Search(view, parse_search("needle"), store.first_seq)
    assert search.nearest(store.first_seq, forward=True) == PENDING
    assert search.nearest(store.first_seq, forward=False) is None  # nothing older than the first row
    steps = 0
    while search.nearest(store.first_seq, forward=True) == PENDING:
        search.step(0.001, prefer=1)
        steps += 1
    assert search.nearest(store.first_seq, forward=True) == 10 * CHUNK_SIZE
    assert steps > 1


def test_arrivals_are_searched_and_evicted_matches_forgotten():
    store = make_store(2 * CHUNK_SIZE, max_messages=3 * CHUNK_SIZE)
    view = LogView(store)
    search = Search(view, parse_search("timeout"), store.end_seq - 1)
    run(search)
    before = search.count()
    store.extend_records(LogRecord(stamp_ns=0, level=20, node="n", msg=f"timeout {i}") for i in range(2 * CHUNK_SIZE))
    view.update()
    assert not search.complete
    run(search)
    assert list(search.seqs()) == brute(view, "timeout")
    assert search.count() < before + 2 * CHUNK_SIZE  # the oldest were evicted


def test_count_before_a_limit():
    store = make_store(1000)
    view = LogView(store)
    search = Search(view, parse_search("ok"), 500)
    run(search)
    expected = brute(view, "ok")
    for limit in (0, 10, 499, 500, 501, 999, 2000):
        assert search.count(limit) == len([s for s in expected if s < limit])


def test_a_catastrophic_regex_is_abandoned(monkeypatch):
    monkeypatch.setattr("console_tui.model.view.search_walk.HITS_LIMIT_S", 0.05)
    store = LogStore()
    store.extend_records(LogRecord(stamp_ns=0, level=20, node="n", msg="a" * 28 + "!") for _ in range(20))
    search = Search(LogView(store), parse_search("/(a+)+$/"), 0)
    assert search.step(5.0)
    assert "too slow" in search.failed


@pytest.mark.parametrize("words", [WORDS, [w for w in WORDS if w.isascii()]], ids=["unicode", "ascii"])
def test_text_hits_on_packed_and_listed_chunks_agree(words):
    store = make_store(CHUNK_SIZE + 100, words=words)
    full, growing = (span.chunk for span in store.spans(0, store.end_seq))
    assert isinstance(full.msgs, PackedTexts) and isinstance(growing.msgs, list)
    rng = random.Random(3)
    spans = [(0, 0), (5, 5), *((lo, lo + rng.randrange(1, 300)) for lo in rng.sample(range(3000), 8))]
    for text in SEARCHES:
        hits = text_hits(parse_search(text))
        predicate = parse_search(text).predicate()
        for chunk in (full, growing):
            for lo, hi in [(10, len(chunk) - 3), *spans]:
                expected = [i for i in range(lo, min(hi, len(chunk))) if predicate(chunk.msgs[i])]
                assert list(hits(chunk, lo, min(hi, len(chunk)))) == expected, (text, lo, hi)


#: Texts, regexes and neither (the plain text every match holds, looked for first, or none).
SEARCHES = (
    "timeout",
    "TIMEOUT",
    "Timeout",
    "größe",
    "Größe 3",
    "nowhere",
    "/out \\d/",
    "/OUT/i",
    "/(?i)timed? ?out/",
    "/^goal/",
    "/Größe \\d+$/",
    "/GRÖSSE/i",
    "/time(out|d out) 1\\d/",
    "/\\d{3}/",
    "/x|ok/",
)


@pytest.mark.parametrize(
    ("text", "holds"),
    [
        ("Timeout", ("Timeout", False)),
        ("timeout", ("timeout", True)),
        ("straße", ("strasse", True)),  # case folding, as the message rule does
        ("größe", ("", False)),
        ("/need(le|ful) \\d+/", ("need", False)),
        ("/NEED(le)?/i", ("need", True)),
        ("/(?i)Need/", ("need", True)),
        ("/a|b/", ("", False)),
        ("/Größe/i", ("", False)),
        ("/a\\x00b/", ("", False)),
    ],
)
def test_must_hold_is_the_plain_text_every_match_holds(text, holds):
    assert must_hold(parse_search(text)) == holds


@pytest.mark.parametrize("forward", [True, False])
def test_seeker_finds_the_nearest_shown_error(forward):
    store = make_store(5 * CHUNK_SIZE)
    view = LogView(store, RuleSet((exclude(MessageRule("ok")),)))
    finish(view)
    start = view.seq_at(len(view) // 2)
    seeker = Seeker(view, level_hits(Severity.ERROR), start, forward=forward)
    while not seeker.step(0.001):
        pass
    rows = range(view.row_of(start) + 1, len(view)) if forward else range(view.row_of(start) - 1, -1, -1)
    expected = next(view.seq_at(r) for r in rows if store.level_of(view.seq_at(r)) >= 40)
    assert seeker.found == expected
    assert view_shows(view, expected)


def test_seeker_says_none_past_the_end_and_stops_at_a_limit():
    store = LogStore()
    store.extend_records(LogRecord(stamp_ns=0, level=20 if i != 90 else 40, node="n", msg="x") for i in range(100))
    view = LogView(store)
    view.clock = lambda: 0.0  # each step runs to its end, however busy the machine
    seeker = Seeker(view, level_hits(40), 95, forward=True)
    assert seeker.step() and seeker.found is None
    seeker = Seeker(view, level_hits(40), 10, forward=True, limit=80)
    assert seeker.step() and seeker.found is None
    seeker = Seeker(view, level_hits(40), 90, forward=True, inclusive=True)
    assert seeker.step() and seeker.found == 90
    seeker = Seeker(view, level_hits(40), 90, forward=False, inclusive=True)
    assert seeker.step() and seeker.found == 90
    seeker = Seeker(view, level_hits(40), 90, forward=False)
    assert seeker.step() and seeker.found is None
