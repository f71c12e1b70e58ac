"""What a regex's shape lets the matcher skip, and that skipping never changes an answer:
the masks equal ``re.search`` on every string, over many generated patterns and strings."""

from __future__ import annotations

import os
import random
import re

import pytest

from console_tui.model.rules.pattern_match import TextMatch
from console_tui.model.rules.regex_shape import literal_alternatives


@pytest.mark.parametrize(
    ("pattern", "expected"),
    [
        ("time(out|d out)", ("timed out", "timeout")),
        ("error|fail(ed|ure)", ("error", "failed", "failure")),
        ("[Tt]imeout", ("Timeout", "timeout")),
        ("colou?r", ("color", "colour")),
        ("ab{2}", ("abb",)),
        (r"\d{3}", None),  # a thousand strings
        ("^goal", None),  # an anchor
        ("a.c", None),
        ("x+", None),  # open repeat
        ("[^a]b", None),
        ("(?i:a)b", None),  # a flag inside
    ],
)
def test_literal_alternatives(pattern, expected):
    assert literal_alternatives(re.compile(pattern)) == expected


PIECES = [
    "a", "b", "ab", "ms", " ms", "time", "out", "d out", "x", "\\d", "\\d{3}", "\\.", ".", ".*", "a+",
    "b?", "[ab]", "[Tt]", "(?:a|b)", "(out|d out)", "\\b", "^", "$", "\\s", "[0-9]{1,2}", "(?=a)", "(?<=b)",
    "é", "SS", "K",
]  # fmt: skip
ALPHABET = [
    "a",
    "b",
    "x",
    " ",
    "m",
    "s",
    "t",
    "i",
    "e",
    "o",
    "u",
    "d",
    "1",
    "2",
    "3",
    ".",
    "A",
    "B",
    "T",
    "é",
    "É",
    "ß",
    "K",
    "\n",
]


def _pattern(rng: random.Random) -> str:
    parts = [rng.choice(PIECES) for _ in range(rng.randint(1, 4))]
    if rng.random() < 0.2:
        parts.insert(rng.randint(0, len(parts)), "|")
    return "".join(parts)


def _string(rng: random.Random) -> str:
    if rng.random() < 0.3:
        return rng.choice(["timeout", "Timed out", "123.4 ms", "12.3 ms and 456.7 ms", "ab ab", "TIME OUT"])
    return "".join(rng.choice(ALPHABET) for _ in range(rng.randint(0, 14)))


@pytest.mark.parametrize("seed", range(int(os.environ.get("CONSOLE_TUI_REGEX_SEEDS", "8"))))
def test_masks_answer_as_re_search_does(seed):
    rng = random.Random(seed)
    strings = [_string(rng) for _ in range(300)]
    tried = 0
    while tried < 150:
        pattern = _pattern(rng)
        ignore_case = rng.random() < 0.5
        try:
            compiled = re.compile(pattern, re.IGNORECASE if ignore_case else 0)
        except re.error:
            continue
        tried += 1
        wanted = bytes(bool(compiled.search(s)) for s in strings)
        got = TextMatch(pattern, ignore_case, regex=True).mask_function()(strings)
        assert got == wanted, (
            pattern,
            ignore_case,
            [s for s, a, b in zip(strings, got, wanted, strict=True) if a != b][:5],
        )


def test_plain_text_ignoring_case_folds_fully():
    strings = ["GRÖSSE", "größe", "Strasse", "STRAßE", "plain", "TIMEOUT", "x"]
    assert TextMatch("größe", ignore_case=True).mask_function()(strings) == bytes([1, 1, 0, 0, 0, 0, 0])
    assert TextMatch("strasse", ignore_case=True).mask_function()(strings) == bytes([0, 0, 1, 1, 0, 0, 0])
    assert TextMatch("timeout", ignore_case=True).mask_function()(strings) == bytes([0, 0, 0, 0, 0, 1, 0])
