"""The row index over the store: unfiltered identity, filtered extension and trimming."""

from console_tui.model.record import LogRecord
from console_tui.model.store import LogStore
from console_tui.model.view import LogView


def fill(store, n, start=0):
    store.extend(LogRecord(stamp_ns=i, level=10 * (1 + i % 5), node="n", msg=str(i)) for i in range(start, start + n))


def warn_and_above(store, span):
    levels = span.chunk.levels
    return [span.seq + i - span.lo for i in range(span.lo, span.hi) if levels[i] >= 30]


def test_unfiltered_rows_are_all_records():
    store = LogStore(max_messages=10)
    view = LogView(store)
    fill(store, 15)
    assert len(view) == 10 and view.seq_at(0) == 5 and view.row_of(7) == 2


def test_filtered_rows_extend_and_trim():
    store = LogStore(max_messages=20)
    view = LogView(store, warn_and_above)
    fill(store, 10)
    view.update()
    assert [view.seq_at(r) for r in range(len(view))] == [2, 3, 4, 7, 8, 9]
    fill(store, 20, start=10)
    view.update()
    assert view.seq_at(0) == 12 and len(view) == 12
    assert view.row_of(13) == 1 and view.row_of(15) == 3
