"""What the log table reads its rows from (``LogTable`` and its parts): a ``LogView``, or
``StormRows`` over one."""

from __future__ import annotations

from typing import Protocol


class TableRows(Protocol):
    """What the table reads its rows from: a ``LogView``, or ``StormRows`` over one."""

    def __len__(self) -> int: ...

    def seq_at(self, row: int) -> int: ...

    def row_of(self, seq: int) -> int: ...

    def count_before(self, seq: int) -> int: ...

    def row_shown(self, seq: int) -> int | None: ...
