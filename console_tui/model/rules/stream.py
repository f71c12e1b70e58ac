"""A rule set applied to a stream of record batches (``console-tui tail``), with the
same semantics and the same rule code as the app's view."""

from __future__ import annotations

from collections.abc import Sequence

from ..record import LogRecord
from ..store import LogStore
from .ruleset import Decoration, RuleSet


class StreamFilter:
    """``filter(batch)``: the records the rules show, each with its decoration
    ("highlight", "dim", or None when no highlight rule is active)."""

    def __init__(self, rules: RuleSet) -> None:
        self.rules = rules
        self._active = rules.active_rules()
        self._highlighting = rules.highlighting

    def filter(self, records: Sequence[LogRecord]) -> list[tuple[LogRecord, Decoration]]:
        if not self._active or not records:
            return [(record, None) for record in records]
        store = LogStore(len(records))
        store.extend(list(records))
        tests = {rule: rule.compile(store) for rule in self._active}
        shown: list[tuple[LogRecord, Decoration]] = []
        done = 0
        for chunk, lo, hi, _seq in store.spans(store.first_seq, store.end_seq):
            masks = {rule: test(chunk, lo, hi) for rule, test in tests.items()}
            visible, highlighted = self.rules.decide(masks, hi - lo)
            for offset, record in enumerate(records[done : done + hi - lo]):
                if visible[offset]:
                    decoration: Decoration = None
                    if self._highlighting:
                        decoration = "highlight" if highlighted[offset] else "dim"
                    shown.append((record, decoration))
            done += hi - lo
        return shown
