"""Each rule's answers, kept per store chunk: a rule is never tested twice on a record.

A ``LogView`` combines these masks under its rule set; switching entries on and off,
inverting them or moving them between exclude and highlight only recombines them, and the
rules pane's counts are read from them.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from ..rules.rule import Rule
from ..store.log_store import CHUNK_SIZE, Chunk

#: ``test(rule, chunk, lo, hi)``: the rule's answers over ``chunk[lo:hi]``, a byte each.
ChunkTest = Callable[[Rule, Chunk, int, int], bytes]


class RuleMasks:
    """Per chunk (by its first seq), per rule: the first offset tested and the answers from there."""

    def __init__(self, first_seq: int) -> None:
        self._masks: dict[int, dict[Rule, list]] = {}
        self._masks_from = first_seq

    def clear(self) -> None:
        self._masks.clear()

    def keep_only(self, rules: Iterable[Rule]) -> None:
        """Forget the answers of rules not among ``rules``."""
        known = set(rules)
        for per_chunk in self._masks.values():
            for rule in [rule for rule in per_chunk if rule not in known]:
                del per_chunk[rule]

    def mask(self, base: int, chunk: Chunk, rule: Rule, lo: int, hi: int, test: ChunkTest) -> bytes:
        """The rule's matches over ``chunk[lo:hi]``, testing only records not tested before."""
        per_chunk = self._masks.setdefault(base, {})
        cached = per_chunk.get(rule)
        if cached is None:
            mask = test(rule, chunk, lo, hi)
            per_chunk[rule] = [lo, bytearray(mask)]
            return mask
        start, mask = cached
        if lo < start:
            mask[0:0] = test(rule, chunk, lo, start)
            cached[0] = start = lo
        end = start + len(mask)
        if hi > end:
            mask.extend(test(rule, chunk, end, hi))
        return bytes(mask[lo - start : hi - start])

    def count(self, rule: Rule, first: int) -> tuple[int, int]:
        """Records from seq ``first`` on that ``rule`` matched, and that it was tested on."""
        self.drop_evicted(first)
        matched = tested = 0
        for base, per_chunk in self._masks.items():
            cached = per_chunk.get(rule)
            if cached is None:
                continue
            start, mask = cached
            skip = min(max(first - base - start, 0), len(mask))
            matched += mask.count(1, skip)
            tested += len(mask) - skip
        return matched, tested

    def drop_from(self, seq: int) -> None:
        """Forget the answers for records from ``seq`` on (the store writes them again)."""
        for base in [base for base in self._masks if base + CHUNK_SIZE > seq]:
            per_chunk = self._masks[base]
            for rule, cached in list(per_chunk.items()):
                keep = seq - base - cached[0]
                if keep <= 0:
                    del per_chunk[rule]
                else:
                    del cached[1][keep:]

    def drop_evicted(self, first: int) -> None:
        """Forget chunks wholly before seq ``first`` (the store dropped them)."""
        if first - self._masks_from >= CHUNK_SIZE:
            for base in [base for base in self._masks if base + CHUNK_SIZE <= first]:
                del self._masks[base]
            self._masks_from = first
