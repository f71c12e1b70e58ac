"""An ordered set of seqs kept compact: a bitmap for each block of seqs, however many there are.

The rows a view shows, the storms' rows and a search's matches are each an ascending set
of store seqs, read by place (``seq_at``: the row's seq; ``rank``: the rows before a seq).
Kept as an ``array`` of seqs they cost 8 bytes a member: 160 MB for a history of 20 million
records that a rule hardly narrows. A ``SeqSet`` keeps one bitmap (a Python ``int``, bit
``i`` for seq ``block * BLOCK + i``) for each block of ``BLOCK`` seqs that has members: at
most 1/8 byte a seq (about 570 bytes a block), and ``int.bit_count`` counts a block at C
speed. Seqs appended one by one (``append``, ``extend``: storms taking records in) wait in
an ``array`` (``_tail``) until the next block begins, and are then folded into their block's
bitmap; a 0/1 mask over consecutive seqs (what a rule's test gives) goes in as a bitmap at
once (``add_mask``), at either end.

A block's place among the rows is the members before it (``_before``, counted from an
origin that may be below 0, so that adding older blocks at the front changes no other
block's entry); a change inside the set (a storm expanded) marks the entries after it to be
counted again when next asked. The members of the blocks read last are kept as arrays
(``_MEMBERS_KEPT``), so a frame that reads the rows on screen turns a bitmap into seqs once.
"""

from __future__ import annotations

from array import array
from bisect import bisect_left, bisect_right
from collections import OrderedDict
from collections.abc import Iterable, Iterator
from itertools import accumulate, compress

from ..store.consecutive import consecutive

BLOCK = 4096
FULL = (1 << BLOCK) - 1
_TO_DIGITS = bytes.maketrans(b"\x00\x01", b"01")
_TO_MASK = bytes.maketrans(b"01", b"\x00\x01")
_OFFSETS = range(BLOCK)
#: Blocks whose members are kept as arrays after being read (a few screens' worth).
_MEMBERS_KEPT = 16


def bits_of(mask: bytes | bytearray) -> int:
    """The bitmap of a 0/1 mask: bit ``i`` set where ``mask[i]`` is 1 (at C speed)."""
    if not mask:
        return 0
    return int(bytes(mask[::-1]).translate(_TO_DIGITS), 2)


def mask_of(bits: int, size: int) -> bytes:
    """The 0/1 mask of the first ``size`` bits of ``bits`` (``bits_of``'s inverse)."""
    if size <= 0:
        return b""
    return format(bits & ((1 << size) - 1), f"0{size}b").encode()[::-1].translate(_TO_MASK)


class SeqSet:
    """Ascending seqs, read by place: ``len``, ``seq_at(row)``, ``rank(seq)``, ``seqs(first, end)``."""

    __slots__ = ("_before", "_bits", "_blocks", "_counts", "_dirty", "_members", "_tail", "_total")

    def __init__(self) -> None:
        self._blocks = array("q")  # block numbers, ascending
        self._bits: list[int] = []
        self._counts = array("q")
        self._before = array("q")  # members before each block, from an origin (valid below _dirty)
        self._dirty = 0
        self._total = 0  # members in the blocks (the tail's not counted)
        self._tail = array("q")  # seqs after the blocks', not folded yet
        self._members: OrderedDict[int, array] = OrderedDict()

    # -- adding -------------------------------------------------------------------------------------

    def append(self, seq: int) -> None:
        """Add ``seq``, greater than every member."""
        tail = self._tail
        if tail and seq // BLOCK != tail[-1] // BLOCK:
            self._fold()
        tail.append(seq)

    def extend(self, seqs: Iterable[int]) -> None:
        """Add ascending ``seqs``, each greater than every member."""
        tail = self._tail
        tail.extend(seqs)
        if tail and tail[0] // BLOCK != tail[-1] // BLOCK:
            self._fold(keep_last=True)

    def add_mask(self, first: int, mask: bytes | bytearray) -> None:
        """Add the seqs ``first + i`` where ``mask[i]`` is 1: all older than every member, or
        all newer (a rule's answers over consecutive records)."""
        if self._tail and first + len(mask) > self._tail[0]:
            self._fold()
        at, end = 0, len(mask)
        while at < end:
            seq = first + at
            block, offset = divmod(seq, BLOCK)
            take = min(BLOCK - offset, end - at)
            piece = mask[at : at + take]
            if piece.count(1):
                self._or_block(block, bits_of(piece) << offset)
            at += take

    def _or_block(self, block: int, bits: int) -> None:
        blocks = self._blocks
        count = bits.bit_count()
        if blocks and block == blocks[-1]:
            index = len(blocks) - 1
        elif blocks and block == blocks[0]:
            index = 0
        else:
            index = bisect_left(blocks, block)
            if index == len(blocks) or blocks[index] != block:
                self._insert_block(index, block, bits, count)
                return
        old = self._bits[index]
        merged = old | bits
        self._set_block(index, merged, merged.bit_count() - old.bit_count())

    def _insert_block(self, index: int, block: int, bits: int, count: int) -> None:
        blocks, before = self._blocks, self._before
        size = len(blocks)
        if index == size:
            valid = self._dirty >= size
            before.append(before[-1] + self._counts[-1] if size and valid else 0)
            if valid:
                self._dirty = size + 1
        elif index == 0:
            self._fix()
            before.insert(0, before[0] - count)  # the blocks after it keep their entries
            self._dirty = size + 1
        else:
            before.insert(index, 0)
            self._dirty = min(self._dirty, index)
        blocks.insert(index, block)
        self._bits.insert(index, bits)
        self._counts.insert(index, count)
        self._total += count

    def _set_block(self, index: int, bits: int, delta: int) -> None:
        """Block ``index`` now holds ``bits`` (``delta`` members more)."""
        self._bits[index] = bits
        self._counts[index] += delta
        self._total += delta
        self._members.pop(self._blocks[index], None)
        if index == 0:
            self._before[0] -= delta  # the blocks after it keep their entries
        elif index < len(self._blocks) - 1:
            self._dirty = min(self._dirty, index + 1)

    def _fold(self, *, keep_last: bool = False) -> None:
        """Fold the tail into blocks (all of it, or all but its last block's seqs)."""
        tail = self._tail
        if not tail:
            return
        end = len(tail)
        if keep_last:
            end = bisect_left(tail, tail[-1] // BLOCK * BLOCK)
        at = 0
        while at < end:
            block = tail[at] // BLOCK
            stop = min(bisect_left(tail, (block + 1) * BLOCK, at), end)
            mask = bytearray(BLOCK)
            base = block * BLOCK
            for seq in tail[at:stop]:
                mask[seq - base] = 1
            self._or_block(block, bits_of(mask))
            at = stop
        del tail[:end]

    def add(self, seqs: Iterable[int]) -> None:
        """Add seqs anywhere (a storm expanded)."""
        self._fold()
        for seq in seqs:
            block, offset = divmod(seq, BLOCK)
            self._or_block(block, 1 << offset)

    def discard(self, seqs: Iterable[int]) -> None:
        """Remove seqs where they are (a storm collapsed)."""
        self._fold()
        blocks = self._blocks
        for seq in seqs:
            block, offset = divmod(seq, BLOCK)
            index = bisect_left(blocks, block)
            if index < len(blocks) and blocks[index] == block and self._bits[index] >> offset & 1:
                self._set_block(index, self._bits[index] & ~(1 << offset), -1)
        self._drop_empty()

    # -- removing at the ends -----------------------------------------------------------------------

    def drop_below(self, first: int) -> None:
        """Forget the members below ``first`` (the store dropped them)."""
        tail = self._tail
        if tail and tail[0] < first:
            del tail[: bisect_left(tail, first)]
        blocks = self._blocks
        if not blocks or blocks[0] * BLOCK >= first:
            return
        self._fix()
        block = first // BLOCK
        gone = bisect_left(blocks, block)
        if gone:
            for number in blocks[:gone]:
                self._members.pop(number, None)
            self._total -= sum(self._counts[:gone])
            del blocks[:gone], self._bits[:gone], self._counts[:gone], self._before[:gone]
            self._dirty = max(self._dirty - gone, 0)
        if blocks and blocks[0] == block:
            old = self._bits[0]
            kept = old & ~((1 << (first - block * BLOCK)) - 1)
            self._set_block(0, kept, kept.bit_count() - old.bit_count())
        self._drop_empty()

    def drop_from(self, seq: int) -> None:
        """Forget the members at ``seq`` and above (the store writes them again)."""
        tail = self._tail
        if tail and tail[-1] >= seq:
            del tail[bisect_left(tail, seq) :]
        blocks = self._blocks
        if not blocks or (blocks[-1] + 1) * BLOCK <= seq:
            return
        block = seq // BLOCK
        keep = bisect_right(blocks, block)
        for number in blocks[keep:]:
            self._members.pop(number, None)
        self._total -= sum(self._counts[keep:])
        del blocks[keep:], self._bits[keep:], self._counts[keep:], self._before[keep:]
        self._dirty = min(self._dirty, len(blocks))
        if blocks and blocks[-1] == block:
            index = len(blocks) - 1
            old = self._bits[index]
            kept = old & ((1 << (seq - block * BLOCK)) - 1)
            self._set_block(index, kept, kept.bit_count() - old.bit_count())
        self._drop_empty()

    def clear(self) -> None:
        self.__init__()  # type: ignore[misc]

    def _drop_empty(self) -> None:
        if 0 in self._counts:
            self._fix()
            keep = [index for index, count in enumerate(self._counts) if count]
            self._blocks = array("q", (self._blocks[i] for i in keep))
            self._bits = [self._bits[i] for i in keep]
            self._counts = array("q", (self._counts[i] for i in keep))
            self._before = array("q", (self._before[i] for i in keep))
            self._dirty = len(self._blocks)

    def _fix(self) -> None:
        """Count the blocks' places again from the first one marked."""
        dirty, blocks = self._dirty, self._blocks
        if dirty >= len(blocks):
            return
        dirty = max(dirty, 1)  # the first block's entry is the origin's
        if dirty < len(blocks):
            start = self._before[dirty - 1] + self._counts[dirty - 1]
            self._before[dirty:] = array("q", accumulate(self._counts[dirty:-1], initial=start))
        self._dirty = len(blocks)

    # -- reading -------------------------------------------------------------------------------------

    def __len__(self) -> int:
        return self._total + len(self._tail)

    def __bool__(self) -> bool:
        return bool(self._total or self._tail)

    def __contains__(self, seq: object) -> bool:
        if not isinstance(seq, int):
            return False
        tail = self._tail
        if tail and seq >= tail[0]:
            at = bisect_left(tail, seq)
            return at < len(tail) and tail[at] == seq
        block, offset = divmod(seq, BLOCK)
        blocks = self._blocks
        index = bisect_left(blocks, block)
        return index < len(blocks) and blocks[index] == block and bool(self._bits[index] >> offset & 1)

    def rank(self, seq: int) -> int:
        """How many members are below ``seq``."""
        tail = self._tail
        if tail and seq > tail[0]:
            return self._total + bisect_left(tail, seq)
        blocks = self._blocks
        if not blocks:
            return 0
        self._fix()
        block, offset = divmod(seq, BLOCK)
        index = bisect_right(blocks, block) - 1
        if index < 0:
            return 0
        before = self._before
        rows = before[index] - before[0]
        if blocks[index] == block:
            return rows + (self._bits[index] & ((1 << offset) - 1)).bit_count()
        return rows + self._counts[index]

    def seq_at(self, row: int) -> int:
        """The member at place ``row`` (0: the smallest); ``IndexError`` past the end."""
        if row < 0:
            raise IndexError(row)
        if row >= self._total:
            return self._tail[row - self._total]
        self._fix()
        before = self._before
        index = bisect_right(before, before[0] + row) - 1
        seq: int = self._members_of(index)[before[0] + row - before[index]]
        return seq

    def seqs(self, first: int, end: int) -> array:
        """The members at places ``first:end`` (clamped), ascending."""
        first, end = max(first, 0), min(end, len(self))
        found = array("q")
        if first >= end:
            return found
        total = self._total
        if first < total:
            self._fix()
            before = self._before
            origin = before[0]
            index = bisect_right(before, origin + first) - 1
            row = first
            while row < min(end, total):
                members = self._members_of(index)
                start = origin + row - before[index]
                take = members[start : start + min(end, total) - row]
                found.extend(take)
                row += len(take)
                index += 1
        if end > total:
            found.extend(self._tail[max(first - total, 0) : end - total])
        return found

    def __iter__(self) -> Iterator[int]:
        for index in range(len(self._blocks)):
            yield from self._members_of(index)
        yield from self._tail

    def first(self) -> int | None:
        return self.seq_at(0) if len(self) else None

    def last(self) -> int | None:
        return self.seq_at(len(self) - 1) if len(self) else None

    def _members_of(self, index: int) -> array:
        """Block ``index``'s members, ascending (kept for the blocks read last)."""
        block = self._blocks[index]
        kept = self._members.get(block)
        if kept is not None:
            self._members.move_to_end(block)
            return kept
        bits, base = self._bits[index], block * BLOCK
        if bits == FULL:
            members = consecutive(base, BLOCK)
        else:
            members = array("q", compress(range(base, base + BLOCK), mask_of(bits, BLOCK)))
        self._members[block] = members
        if len(self._members) > _MEMBERS_KEPT:
            self._members.popitem(last=False)
        return members

    @property
    def nbytes(self) -> int:
        """About the memory the set holds (its bitmaps, arrays and tail)."""
        bitmaps = sum(bits.bit_length() // 8 + 28 for bits in self._bits)
        return 32 * len(self._blocks) + bitmaps + 8 * len(self._tail)
