"""Matching on packed messages all at once answers exactly as matching them one by one."""

from __future__ import annotations

import random

import pytest

from console_tui.model.rules import packed_match
from console_tui.model.rules.message import messages_test
from console_tui.model.rules.pattern_match import TextMatch
from console_tui.model.rules.regex_shape import row_safety
from console_tui.model.store.log_store import Chunk
from console_tui.model.store.packed_texts import PackedTexts, pack

WORDS = [
    "time",
    "out",
    "timeout",
    "Timed out",
    "TIMEOUT",
    "ms",
    " ms",
    "123.4 ms",
    "12.3 ms",
    "frame",
    "frames",
    "aaa",
    "aa",
    "a",
    "x",
    "foo",
    "bar",
    "K",
    "k",
    "error",
    "0.25 rad",
    "\t",
    " ",
    ".",
    "-",
    "9",
]


def messages(seed: int, count: int = 300) -> list[str]:
    rng = random.Random(seed)
    return [
        "".join(rng.choice(WORDS) + rng.choice(["", " ", "_"]) for _ in range(rng.randrange(0, 8)))
        for _ in range(count)
    ]


def packed_chunk(texts: list[str]) -> Chunk:
    chunk = Chunk()
    chunk.msgs = pack(texts)
    assert isinstance(chunk.msgs, PackedTexts)
    return chunk


CASES = [
    ("timeout",),
    ("ms",),
    (" ms",),
    ("aa",),
    ("",),
    ("K", True),
    ("timeout", True),
    ("\0",),
    ("\0", True),
    ("time(out|d out)", True, True),
    ("time(out|d out)", False, True),
    (r"\d{3}\.\d ms", False, True),
    (r"\d+\.\d ms", False, True),
    (r"aa+", False, True),
    (r"a(a|)", False, True),
    (r"\bframe\b", True, True),
    (r"^time", False, True),
    (r"out$", False, True),
    (r"(?<=time)out", False, True),
    (r"foo.*bar", False, True),
    (r"foo[^x]bar", False, True),
    (r"(a)\1a", False, True),
    (r"x|foo", True, True),
    (r"[0-9]{2}", False, True),
    (r"out(?=\s)", False, True),
    (r"(?i)k", False, True),
    (r"frame\W", False, True),
    (r"aaa\d", False, True),
]


@pytest.mark.parametrize("args", CASES, ids=repr)
@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("dense", [False, True], ids=["usual", "any-number-of-occurrences"])
def test_packed_answers_as_one_by_one(args, seed, dense, monkeypatch):
    if dense:  # the packed way answers however often the text occurs
        monkeypatch.setattr(packed_match, "OCCURRENCES_PER_ROW", 1000.0)
        monkeypatch.setattr(packed_match, "REGEX_OCCURRENCES_PER_ROW", 1000.0)
    match = TextMatch(*args)
    texts = messages(seed)
    chunk = packed_chunk(texts)
    expected = match.mask_function()
    test = messages_test(match)
    for lo, hi in [(0, len(texts)), (0, 1), (5, 77), (100, len(texts)), (299, 300)]:
        assert test(chunk, lo, hi) == expected(texts[lo:hi]), (lo, hi)


def test_non_ascii_text_ignoring_case_is_tested_one_by_one():
    texts = ["Größe 3 timeout", "GRÖSSE", "plain", "K timeout"]
    chunk = packed_chunk(texts)
    for args in [("grösse", True), ("k", True), ("TIMEOUT", True), ("timeout", True, True)]:
        match = TextMatch(*args)
        assert messages_test(match)(chunk, 0, 4) == match.mask_function()(texts)


def test_row_safety_reads_the_pattern():
    import re

    safe = {p: row_safety(re.compile(p)) for p in [r"\d{3}\.\d ms", r"foo.*bar", r"^foo", r"\bfoo", r"(?<=x)y"]}
    assert (safe[r"\d{3}\.\d ms"].bounded, safe[r"\d{3}\.\d ms"].nul_free) == (True, True)
    assert (safe[r"foo.*bar"].bounded, safe[r"foo.*bar"].nul_free) == (True, False)
    assert (safe[r"\bfoo"].bounded, safe[r"\bfoo"].nul_free) == (True, True)
    assert not safe[r"^foo"].bounded and not safe[r"(?<=x)y"].bounded


def test_the_packed_way_answers_where_it_can(monkeypatch):
    monkeypatch.setattr(packed_match, "OCCURRENCES_PER_ROW", 1000.0)
    monkeypatch.setattr(packed_match, "REGEX_OCCURRENCES_PER_ROW", 1000.0)
    chunk = packed_chunk(messages(1))
    for args in [
        ("ms",),
        ("K", True),
        ("time(out|d out)", True, True),
        (r"\d{3}\.\d ms", False, True),
        ("foo.*bar", 0, 1),
    ]:
        matcher = TextMatch(*args).packed_matcher()
        assert matcher is not None and matcher(chunk.msgs, 0, 300) is not None, args
    for args in [("",), (r"^time", False, True), (r"[0-9]{2}", False, True), (r"out(?=\s)", False, True)]:
        assert TextMatch(*args).packed_matcher() is None, args
