"""A full chunk's messages packed: joined, compressed, and read back as they were."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from console_tui.model.store import packed_texts
from console_tui.model.store.packed_texts import RECENT, PackedTexts, pack


def forget_recent() -> None:
    """Every chunk read before is read again from its compressed form."""
    for _ in range(RECENT):
        pack(["pushes the others out"])


def reads_like(packed: PackedTexts | list[str], texts: list[str]) -> None:
    assert list(packed) == texts and len(packed) == len(texts)
    assert [packed[i] for i in range(len(texts))] == texts
    assert [packed[i] for i in range(-len(texts), 0)] == texts
    assert list(packed[1:]) == texts[1:] and list(packed[::2]) == texts[::2] and list(packed[::-1]) == texts[::-1]


HUGE = "x" * 3_000_000
CASES = {
    "plain": ["a", "", "bc"],
    "empty": [""],
    "all empty": [""] * 5000,
    "wide": ["☃"] + ["plain ascii text " * 12] * 50,
    "non-ascii": ["ünïcødé", "日本語のログ", "emoji 🤖 here", "plain"],
    "lone surrogates": ["\udcff\udc80 undecodable bytes kept", "\ud83d", "a\udfffb"],
    "escapes": ["\x1b[31mred\x1b[0m", "tab\there", "new\nline", "\r"],
    "huge": ["before", HUGE, "after"],
}


@pytest.mark.parametrize("texts", list(CASES.values()), ids=list(CASES))
def test_pack_reads_like_the_texts_fresh_and_from_its_compressed_form(texts):
    packed = pack(texts)
    assert isinstance(packed, PackedTexts)
    reads_like(packed, texts)
    forget_recent()
    assert packed._text is None and packed._texts is None
    reads_like(packed, texts)
    forget_recent()
    assert [packed[i] for i in range(len(texts))] == texts  # one at a time, from the compressed form
    forget_recent()
    assert packed[1:2] == texts[1:2]  # a small slice, from the compressed form
    assert packed.text == "\0".join(texts) and packed.starts[-1] == len(packed.text) + 1


def test_texts_holding_nul_stay_a_list_and_no_texts_are_no_pack():
    texts = ["one\0two", "x"]
    assert pack(texts) is texts
    assert pack([]) == []


def test_a_log_is_kept_in_a_fraction_of_its_size():
    texts = [f"Costmap updated in {i % 97}.{i % 10} ms: {i % 13} obstacles, origin ({i % 7}, 3)" for i in range(4096)]
    packed = pack(texts)
    assert isinstance(packed, PackedTexts)
    assert packed.nbytes < sum(map(len, texts)) / 2


def test_only_the_recent_chunks_keep_their_texts_made():
    chunks = [pack([f"chunk {n} text {i}" for i in range(100)]) for n in range(RECENT + 3)]
    for chunk in chunks:
        assert isinstance(chunk, PackedTexts)
        chunk.texts()
    made = [chunk for chunk in chunks if chunk._text is not None or chunk._texts is not None]  # type: ignore[union-attr]
    assert made == chunks[-RECENT:]
    assert len(packed_texts._recent) == RECENT


def test_packs_of_the_same_texts_are_equal():
    texts = ["same", "texts"]
    assert pack(texts) == pack(list(texts)) and pack(texts) != pack(["other", "texts"])


@settings(max_examples=200, deadline=None)
@given(st.lists(st.text(st.characters(exclude_characters="\0", exclude_categories=())), min_size=1, max_size=40))
def test_any_texts_without_nul_read_back_as_they_were(texts):
    packed = pack(texts)
    assert isinstance(packed, PackedTexts)
    forget_recent()
    reads_like(packed, texts)
