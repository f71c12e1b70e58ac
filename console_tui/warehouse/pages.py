"""A window of ``otel_logs`` read page by page, in time order, each row once.

The rows of a window (``--since``/``--until``, the rules' SQL: ``pushdown.where``) are read
by their ``Timestamp``: ``newest(n)`` the newest ``n``; ``older(n)`` the ``n`` before the
oldest read; ``newer(n)`` those after the newest (and those that reached the table late, up to
``LOOKBACK_NS`` behind it: a robot's batch lands after another's newer one); ``first(n)`` the
window's start for reading it forward (``tail``, ``convert``), ``forward(n)`` onward. Each
page comes oldest first, as ``RecordColumns``.

Every page is two queries: the bounding ``Timestamp`` (the ``n``-th row, which reads only
the timestamps and what the conditions test), then the rows from it. Rows with the same
``Timestamp`` and content (a batch sent twice, after a shipper's crash) are one record: a row's
``identity`` (a hash of its content, in SQL) is remembered for the rows at a page's edge and in
the lookback. A page is at most ``MAX_PAGE_ROWS`` rows; each query runs with the client's time
limit.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import chain, compress
from typing import Any

from ..model.store.record_batch import RecordColumns
from .clickhouse import TableClient
from .pushdown import window_sql
from .schema import RECORD_COLUMNS

MAX_PAGE_ROWS = 200_000
#: How far behind the newest row a row may reach the table and still be found by ``newer``.
LOOKBACK_NS = 15_000_000_000
#: The spans of time, back from the newest row, in which a page's bound is looked for in turn:
#: ten minutes, three times as long each time (a span too short costs a third of the next),
#: to fifteen days; then the whole table.
SPANS_S = tuple(600 * 3**step for step in range(8))
#: Rows at one ``Timestamp`` beyond a page's count read to keep a group whole.
TIE_ROOM = 1_000
_SELECT = ", ".join(expression for _, expression in RECORD_COLUMNS)
#: A row's identity in SQL (a hash of its content).
IDENTITY = dict(RECORD_COLUMNS)["identity"]
#: Identities of late rows asked for in one query.
LATE_IDS_A_QUERY = 2_000
_IDENTITY = len(RECORD_COLUMNS) - 2
_VALID = len(RECORD_COLUMNS) - 1


def _ns(stamp: int) -> str:
    return f"fromUnixTimestamp64Nano(toInt64({int(stamp)}))"


class Abandoned(Exception):
    """A page given up between two of its queries: ``abandoned()`` said so."""


class TablePages:
    """Reads one window of the table through ``client``; ``condition`` is SQL over a row.
    ``abandoned`` is asked before each query: when it holds, the page is given up
    (``Abandoned``), so that new rules wait for one query at most, not a page's several."""

    def __init__(
        self,
        client: TableClient,
        condition: str = "1",
        *,
        source: str = "",
        abandoned: Callable[[], bool] = lambda: False,
    ) -> None:
        self.client = client
        self.abandoned = abandoned
        self.condition = condition or "1"
        self.source = source
        #: The oldest and newest ``Timestamp`` read.
        self.oldest_ns: int | None = None
        self.newest_ns: int | None = None
        #: The identities of the rows read at the oldest ``Timestamp``.
        self._oldest_ids: set[int] = set()
        #: The identities of the rows read in the lookback behind the newest, with their stamps.
        self._recent: dict[int, int] = {}
        #: Rows read whose message was not UTF-8 (shown repaired), and rows stored twice (shown once).
        self.repaired = 0
        self.duplicates = 0
        #: Nothing older is left in the window.
        self.at_start = False
        #: The second of the table's oldest row, when asked (a span reaching it is the whole table).
        self._table_oldest_s: int | None = None

    # -- queries ---------------------------------------------------------------------------------

    def _go_on(self) -> None:
        """Before each query: ``Abandoned`` once ``abandoned()`` holds."""
        if self.abandoned():
            raise Abandoned

    def _columns(self, sql: str) -> list[Sequence[Any]]:
        self._go_on()
        return self.client.columns(sql)

    def _where(self, where: str) -> str:
        return f"({self.condition}) AND ({where})"

    def _rows(self, where: str, order: str, limit: int, *, span: str = "") -> list[list[Any]]:
        """Rows, ``span`` (a condition on the time) read first (``PREWHERE``): the rest of a row,
        its maps and message, only where it holds; on an engine that can, only for the rows
        the ``LIMIT`` keeps (lazy materialization)."""
        prewhere = f"PREWHERE {span} " if span not in ("", "1") else ""
        sql = (
            f"SELECT {_SELECT} FROM {self.client.table} {prewhere}WHERE {self._where(where)} "
            f"ORDER BY Timestamp {order} LIMIT {int(limit)}{self.client.lazy_rows(limit)}"
        )
        return [list(column) for column in self._columns(sql)]

    def _bound(self, where: str, order: str, offset: int) -> int | None:
        """The ``Timestamp`` of the row ``offset`` rows into the order, or None past the end."""
        sql = (
            f"SELECT toUnixTimestamp64Nano(Timestamp) FROM {self.client.table} WHERE {self._where(where)} "
            f"ORDER BY Timestamp {order} LIMIT 1 OFFSET {int(offset)}"
        )
        self._go_on()
        value = self.client.value(sql)
        return None if value is None else int(value)

    # -- backward: the newest rows, then older ones ------------------------------------------------

    def newest(self, count: int) -> RecordColumns:
        """The newest ``count`` rows of the window (and the rest of their oldest ``Timestamp``)."""
        return self._backward("1", count)

    def older(self, count: int) -> RecordColumns:
        """The ``count`` rows before the oldest read."""
        if self.oldest_ns is None:
            return self.newest(count)
        return self._backward(window_sql(None, self.oldest_ns), count)

    def _newest_bound(self, where: str, offset: int, top_ns: int | None) -> int | None:
        """``_bound`` going back from ``top_ns`` (the newest row: None) in growing spans of time
        (``SPANS_S``), so that a page of recent rows reads only the recent part of the table
        (the partitions, and the primary key's ``TimestampTime``, leave the rest unread)."""
        if top_ns is None or self._table_oldest_s is None:
            # The table's oldest and newest rows (the table's, not the window's: one cheap column).
            columns = self._columns(
                f"SELECT toUnixTimestamp64Nano(min(Timestamp)), toUnixTimestamp64Nano(max(Timestamp)) "
                f"FROM {self.client.table}"
            )
            oldest, newest = (int(column[0]) if len(column) else 0 for column in columns)
            if not newest:
                return None
            self._table_oldest_s = oldest // 1_000_000_000
            top_ns = newest if top_ns is None else top_ns
        for span in SPANS_S:
            floor_s = top_ns // 1_000_000_000 - span
            if floor_s <= self._table_oldest_s:  # the span holds the whole table: no span at all
                break
            bound = self._bound(f"({where}) AND TimestampTime >= toDateTime({floor_s})", "DESC", offset)
            if bound is not None:
                return bound
        return self._bound(where, "DESC", offset)

    def _backward(self, where: str, count: int) -> RecordColumns:
        count = min(max(count, 1), MAX_PAGE_ROWS)
        # Past the rows read at the oldest time (they are asked again: ``<=``), ``count`` more.
        bound = self._newest_bound(where, count - 1 + len(self._oldest_ids), self.oldest_ns)
        span = window_sql(bound, None)
        limit = count + TIE_ROOM + len(self._oldest_ids)
        columns = [column[::-1] for column in self._rows(where, "DESC", limit, span=span)]
        page = self._page(columns, self._oldest_ids)
        if bound is None:  # fewer rows than asked for: these were the oldest
            self.at_start = True
        stamps = columns[0] if columns else []
        if stamps:
            first = int(stamps[0])
            self._remember_recent(columns)  # what is read is never late (``newer``)
            if self.oldest_ns is None or first < self.oldest_ns:
                self._oldest_ids = set()
            self.oldest_ns = first
            self._oldest_ids |= {int(i) for s, i in zip(stamps, columns[_IDENTITY], strict=True) if int(s) == first}
        return page

    # -- forward: following the tail, reading a window from its start --------------------------

    def newer(self, count: int) -> RecordColumns:
        """Rows after the newest read (at most ``count``), and before them those that reached the
        table late, up to ``LOOKBACK_NS`` behind it."""
        if self.newest_ns is None:
            return self.newest(count)
        newest, since = self.newest_ns, self.newest_ns - LOOKBACK_NS
        if self.oldest_ns is not None:  # rows before the oldest read are older, not late
            since = max(since, self.oldest_ns)
        span = window_sql(since, newest)
        identities = self._columns(f"SELECT {IDENTITY} FROM {self.client.table} WHERE {self._where(span)}")
        late = sorted({int(i) for i in (identities[0] if identities else [])} - self._recent.keys())
        parts = []
        for start in range(0, len(late), LATE_IDS_A_QUERY):
            ids = ", ".join(str(i) for i in late[start : start + LATE_IDS_A_QUERY])
            parts.append(self._rows(f"{span} AND {IDENTITY} IN ({ids})", "ASC", LATE_IDS_A_QUERY * 2))
        newer = f"Timestamp > {_ns(newest)} AND {window_sql(newest, None)}"
        parts.append(self._rows("1", "ASC", min(count, MAX_PAGE_ROWS), span=newer))
        columns = [list(chain.from_iterable(part[i] for part in parts if part)) for i in range(len(RECORD_COLUMNS))]
        if columns[0]:
            order = sorted(range(len(columns[0])), key=columns[0].__getitem__)
            columns = [[column[i] for i in order] for column in columns]
        page = self._page(columns, set(self._recent))
        self._remember_recent(columns)
        return page

    def first(self, count: int, within: int | None = None) -> RecordColumns:
        """The window's first page for reading it forward (``forward``): from its start, or with
        ``within`` from the ``within``-th newest row (``--max-messages``)."""
        self.newest_ns, self.oldest_ns, self._recent = None, None, {}
        if within is not None:
            bound = self._bound("1", "DESC", max(within, 1) - 1)
            if bound is not None:
                self.newest_ns = bound
        return self.forward(count)

    def forward(self, count: int) -> RecordColumns:
        """The next ``count`` rows after the newest read, in order (a ``Timestamp``'s rows kept whole)."""
        count = min(max(count, 1), MAX_PAGE_ROWS)
        bound = self._bound(window_sql(self.newest_ns, None), "ASC", count - 1)
        span = window_sql(self.newest_ns, bound)
        edge = {i for i, s in self._recent.items() if s == self.newest_ns}
        columns = self._rows("1", "ASC", count + TIE_ROOM + len(edge), span=span)
        page = self._page(columns, edge)
        stamps = columns[0] if columns else []
        if stamps:
            if self.oldest_ns is None:
                self.oldest_ns = int(stamps[0])
            last = int(stamps[-1])
            self._recent = {i: s for i, s in self._recent.items() if s == last}
            self.newest_ns = last
            for stamp, identity in zip(stamps, columns[_IDENTITY], strict=True):
                if int(stamp) == last:
                    self._recent[int(identity)] = last
        return page

    # -- rows into records -----------------------------------------------------------------------

    def _remember_recent(self, columns: list[list[Any]]) -> None:
        stamps = columns[0] if columns else []
        if not stamps:
            return
        newest = max(int(stamps[-1]), self.newest_ns if self.newest_ns is not None else int(stamps[-1]))
        self.newest_ns = newest
        floor = newest - LOOKBACK_NS
        recent = {i: s for i, s in self._recent.items() if s >= floor}
        for stamp, identity in zip(stamps, columns[_IDENTITY], strict=True):
            if int(stamp) >= floor:
                recent[int(identity)] = int(stamp)
        self._recent = recent

    def _page(self, columns: list[list[Any]], known: set[int] | dict[int, int]) -> RecordColumns:
        """Rows (in time order) as records, without those read before (``known``) and without a
        row's second copy."""
        if not columns or not columns[0]:
            return RecordColumns([], [], [], [], [], [], [], [])
        seen = set(known)
        keep = bytearray(len(columns[0]))
        copies = 0
        for index, identity in enumerate(columns[_IDENTITY]):
            if identity in seen:
                copies += identity not in known
            else:
                seen.add(identity)
                keep[index] = 1
        self.duplicates += copies
        if keep.count(0):
            columns = [list(compress(column, keep)) for column in columns]
        stamps, levels, nodes, msgs, files, functions, lines, topics, robots = columns[:9]
        self.repaired += len(columns[_VALID]) - sum(columns[_VALID])
        return RecordColumns(
            stamps,
            levels,
            nodes,
            msgs,
            files,
            functions,
            lines,
            [self.source] * len(msgs),
            topics if any(topics) else None,
            robots if any(robots) else None,
        )
