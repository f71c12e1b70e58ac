"""What the status line says of the history: records dropped at the bound, and why full
chunks stay in memory (a full disk, a cache directory refused)."""

from __future__ import annotations

from typing import NamedTuple

from ..inert_text import one_line
from .log_store import LogStore


class HistoryState(NamedTuple):
    """The status line's words for the history (``text``, in a narrow line ``short``);
    ``problem``: said as a problem (the history is not going to disk)."""

    text: str
    short: str
    problem: bool


def history_state(store: LogStore) -> HistoryState | None:
    """What to say of ``store``'s history, or None while there is nothing to say."""
    why = store.spill_problem or (store.memory_reason if store.spill is None else "")
    dropped = f"{store.evicted:,} dropped" if store.evicted else ""
    if why:
        bound = f"{store.memory_bound:,}"
        text = f"history in memory (at most {bound}): {one_line(why, 200)}"
        short = "disk full: history in memory" if "space" in why.lower() else "history in memory"
        if dropped:
            text, short = f"{dropped}; {text}", f"{dropped}; {short}"
        return HistoryState(text, short, True)
    changed = store.spill.read_problem if store.spill is not None else ""
    if changed:
        return HistoryState(f"{dropped}; {changed}" if dropped else changed, "file changed", True)
    if dropped:
        return HistoryState(f"{dropped} (the oldest, at the bound of {store.bound:,})", dropped, False)
    return None
