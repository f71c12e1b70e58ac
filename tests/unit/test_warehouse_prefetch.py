"""The warehouse's prefetch reads pieces sized by how long the last one took, so that rules
changed while it runs wait for a short query at most (no engine: the sizes alone)."""

from __future__ import annotations

from console_tui.sources.warehouse_source import (
    MAX_PREFETCH_PIECE,
    MIN_PREFETCH_PIECE,
    PIECE_BUDGET_S,
    PREFETCH_PIECE,
    next_piece,
)


def test_a_piece_read_within_the_budget_doubles_up_to_the_most():
    piece, sizes = PREFETCH_PIECE, []
    for _ in range(8):
        piece = next_piece(piece, PIECE_BUDGET_S / 2)
        sizes.append(piece)
    assert sizes[:2] == [2 * PREFETCH_PIECE, 4 * PREFETCH_PIECE]
    assert sizes[-1] == MAX_PREFETCH_PIECE and sorted(sizes) == sizes


def test_a_slow_piece_halves_down_to_the_least():
    assert next_piece(PREFETCH_PIECE, PIECE_BUDGET_S * 4) == PREFETCH_PIECE // 2
    piece = PREFETCH_PIECE
    for _ in range(10):
        piece = next_piece(piece, 5.0)
    assert piece == MIN_PREFETCH_PIECE
