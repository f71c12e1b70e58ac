"""SeqSet: an ordered set of seqs as bitmaps per block, against a sorted list doing the same."""

from __future__ import annotations

from bisect import bisect_left

from hypothesis import given, settings
from hypothesis import strategies as st

from console_tui.model.view.seq_set import BLOCK, SeqSet, bits_of, mask_of

SPAN = 5 * BLOCK


def check(seqs: SeqSet, reference: list[int]) -> None:
    assert len(seqs) == len(reference)
    assert list(seqs) == reference
    for row in {0, len(reference) // 3, len(reference) // 2, len(reference) - 1}:
        if 0 <= row < len(reference):
            assert seqs.seq_at(row) == reference[row]
    for seq in {0, 1, BLOCK - 1, BLOCK, BLOCK + 7, 3 * BLOCK + 100, SPAN, *reference[:3], *reference[-3:]}:
        assert seqs.rank(seq) == bisect_left(reference, seq)
        assert (seq in seqs) == (seq in reference)
    third = len(reference) // 3
    assert seqs.seqs(third, 2 * third + 5).tolist() == reference[third : 2 * third + 5]


@st.composite
def operations(draw: st.DrawFn) -> list[tuple]:
    steps = []
    for _ in range(draw(st.integers(1, 12))):
        kind = draw(st.sampled_from(["append", "extend", "mask", "add", "discard", "below", "from"]))
        if kind in ("append", "extend"):
            steps.append((kind, draw(st.lists(st.integers(1, 3000), min_size=1, max_size=60))))
        elif kind == "mask":
            steps.append(
                (kind, draw(st.booleans()), draw(st.binary(min_size=1, max_size=6000)), draw(st.integers(0, 900)))
            )
        elif kind in ("add", "discard"):
            steps.append((kind, draw(st.lists(st.integers(0, SPAN), max_size=30))))
        else:
            steps.append((kind, draw(st.integers(0, SPAN))))
    return steps


@settings(max_examples=150, deadline=None)
@given(operations())
def test_seq_set_against_a_sorted_list(steps):
    seqs, reference = SeqSet(), []
    for step in steps:
        kind = step[0]
        if kind in ("append", "extend"):
            start = (reference[-1] + 1) if reference else 0
            new = []
            for gap in step[1]:
                start += gap - 1
                new.append(start)
                start += 1
            if kind == "append":
                for seq in new:
                    seqs.append(seq)
            else:
                seqs.extend(new)
            reference += new
        elif kind == "mask":
            newer, raw, gap = step[1], step[2], step[3]
            mask = bytes(byte & 1 for byte in raw)
            if newer or not reference:
                first = (reference[-1] + 1 + gap) if reference else gap
            else:
                first = reference[0] - len(mask) - gap
                if first < 0:
                    continue
            seqs.add_mask(first, mask)
            reference = sorted(set(reference) | {first + i for i, bit in enumerate(mask) if bit})
        elif kind == "add":
            seqs.add(step[1])
            reference = sorted(set(reference) | set(step[1]))
        elif kind == "discard":
            seqs.discard(step[1])
            reference = sorted(set(reference) - set(step[1]))
        elif kind == "below":
            seqs.drop_below(step[1])
            reference = [seq for seq in reference if seq >= step[1]]
        else:
            seqs.drop_from(step[1])
            reference = [seq for seq in reference if seq < step[1]]
        check(seqs, reference)


def test_bits_and_masks_round_trip():
    mask = bytes([1, 0, 0, 1, 1] * 900)
    assert mask_of(bits_of(mask), len(mask)) == mask
    assert bits_of(b"") == 0 and mask_of(5, 0) == b""


def test_a_history_of_millions_costs_bits_not_words():
    seqs = SeqSet()
    for block in range(500):
        seqs.add_mask(block * BLOCK, b"\x01" * BLOCK)
    assert len(seqs) == 500 * BLOCK
    assert seqs.nbytes < len(seqs) // 4  # under 2 bits a member (an array: 64)
    assert seqs.seq_at(123_456) == 123_456 and seqs.rank(2_000_000) == 2_000_000
