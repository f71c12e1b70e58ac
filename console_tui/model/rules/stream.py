"""A rule set applied to a stream of record batches (``console-tui tail``), with the
same semantics and the same rule code as the app's view.

As in the view, a rule whose test of a batch runs past ``RULE_LIMIT_S`` (a catastrophic
regex) is switched off and listed in ``switched_off``; the other rules go on."""

from __future__ import annotations

from collections.abc import Sequence

from ..inert_text import plural
from ..store.log_store import Chunk, LogStore
from ..store.record import LogRecord
from .rule import Rule, SpanTest
from .ruleset import Decoration, RuleSet
from .time_limit import MatchTimeout, time_limit

#: Longest one test of a rule over a batch may take before the rule counts as too slow.
RULE_LIMIT_S = 0.25


class StreamFilter:
    """``filter(batch)``: the records the rules show, each with its decoration
    ("highlight", "dim", or None when no highlight rule is active)."""

    def __init__(self, rules: RuleSet, *, rule_limit_s: float = RULE_LIMIT_S) -> None:
        self.rules = rules
        self.rule_limit_s = rule_limit_s
        #: Rules switched off as too slow, with why (the caller tells and clears it).
        self.switched_off: list[tuple[Rule, str]] = []
        self._use(rules)

    def _use(self, rules: RuleSet) -> None:
        self.rules = rules
        self._active = rules.active_rules()
        self._highlighting = rules.highlighting

    def filter(self, records: Sequence[LogRecord]) -> list[tuple[LogRecord, Decoration]]:
        if not self._active or not records:
            return [(record, None) for record in records]
        store = LogStore(len(records))
        store.extend_records(records)
        tests = {rule: rule.compile(store) for rule in self._active}
        shown: list[tuple[LogRecord, Decoration]] = []
        done = 0
        for chunk, lo, hi, _seq in store.spans(store.first_seq, store.end_seq):
            masks = {rule: self._test(rule, test, chunk, lo, hi) for rule, test in tests.items()}
            if self.rules.active_rules() != self._active:  # a rule was switched off: again without it
                return self.filter(records)
            visible, highlighted = self.rules.decide(masks, hi - lo)
            for offset, record in enumerate(records[done : done + hi - lo]):
                if visible[offset]:
                    decoration: Decoration = None
                    if self._highlighting:
                        decoration = "highlight" if highlighted[offset] else "dim"
                    shown.append((record, decoration))
            done += hi - lo
        return shown

    def _test(self, rule: Rule, test: SpanTest, chunk: Chunk, lo: int, hi: int) -> bytes:
        try:
            with time_limit(self.rule_limit_s):
                return test(chunk, lo, hi)
        except MatchTimeout:
            why = f"too slow: testing {plural(hi - lo, 'message')} took over {self.rule_limit_s:g} s"
            self.switched_off.append((rule, why))
            self._use(self.rules.without_rules({rule}))
            return bytes(hi - lo)
