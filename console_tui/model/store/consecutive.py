"""Runs of consecutive seqs as arrays, built fast (a view's rows where every record shows)."""

from __future__ import annotations

import sys
from array import array

from .log_store import CHUNK_SIZE

#: 1 in every 8-byte lane, and each lane's index, for CHUNK_SIZE lanes (``consecutive``).
_LANES = 8 * CHUNK_SIZE
_ONES = int.from_bytes(array("q", [1] * CHUNK_SIZE).tobytes(), sys.byteorder)
_INDEXES = int.from_bytes(array("q", range(CHUNK_SIZE)).tobytes(), sys.byteorder)


def consecutive(first: int, count: int, *, descending: bool = False) -> array:
    """``array("q", range(first, first + count))`` (reversed when ``descending``), built as
    one big integer, one 64-bit lane per seq, instead of one Python int per seq."""
    if count > CHUNK_SIZE or count <= 0:
        values = range(first, first + count)
        return array("q", reversed(values) if descending else values)
    keep = (1 << (64 * count)) - 1
    ones, indexes = _ONES & keep, _INDEXES & keep
    value = (first + count - 1) * ones - indexes if descending else first * ones + indexes
    seqs = array("q")
    seqs.frombytes(value.to_bytes(8 * count, sys.byteorder))
    return seqs


def shifted(values: array, delta: int) -> array:
    """``array("q", (value + delta for value in values))`` for at most ``CHUNK_SIZE`` values
    that stay at 0 or more (seqs to offsets in a chunk and back), as one big-integer sum."""
    count = len(values)
    if count > CHUNK_SIZE or not count:
        return array("q", (value + delta for value in values))
    value = int.from_bytes(values.tobytes(), sys.byteorder) + delta * (_ONES & ((1 << (64 * count)) - 1))
    result = array("q")
    result.frombytes(value.to_bytes(8 * count, sys.byteorder))
    return result
