"""The log table's columns and how they share the width."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass


@dataclass(frozen=True)
class Column:
    """A table column. ``drop_order``: columns with lower numbers give way first when narrow."""

    key: str
    title: str
    width: int
    align: str = "left"
    flex: bool = False
    drop_order: int = 99
    shown_by_default: bool = True


#: Narrow, the columns give way in this order (``drop_order``): function, line, file, source,
#: then the row number, the time and the robot (a fleet's) last: what a person needs at 80 columns is the row number,
#: the time, the severity, a node name that tells nodes apart, and as much of the message as fits.
COLUMNS: tuple[Column, ...] = (
    Column("seq", "#", 7, align="right", drop_order=5),
    Column("time", "Time", 12, drop_order=6),
    Column("severity", "Sev", 5),
    Column("robot", "Robot", 8, drop_order=7, shown_by_default=False),
    Column("node", "Node", 16),
    Column("message", "Message", 24, flex=True),
    Column("file", "File", 16, drop_order=3),
    Column("function", "Function", 14, drop_order=1),
    Column("line", "Line", 5, align="right", drop_order=2),
    Column("source", "Source", 20, drop_order=4, shown_by_default=False),
)
COLUMN_KEYS = tuple(column.key for column in COLUMNS)
BY_KEY = {column.key: column for column in COLUMNS}
MESSAGE_MIN = 24


def message_min(width: int) -> int:
    """The narrowest the message column may get before optional columns give way: a third of
    the width (26 of 80 columns, 53 of 160)."""
    return max(MESSAGE_MIN, width // 3)


SEPARATOR = 1


@dataclass(frozen=True)
class PlacedColumn:
    column: Column
    x: int
    width: int


def layout_columns(
    width: int, shown: frozenset[str], node_width: int, widths: Mapping[str, int] | None = None
) -> tuple[PlacedColumn, ...]:
    """Place the shown columns in ``width`` cells, dropping optional ones while the
    message column would be narrower than ``message_min(width)``; the message takes the rest.
    ``widths`` overrides columns' widths (the Time column's follows its format)."""
    widths = widths or {}

    def sized(column: Column) -> int:
        return node_width if column.key == "node" else widths.get(column.key, column.width)

    columns = [column for column in COLUMNS if column.key in shown]
    while True:
        fixed = sum(sized(c) + SEPARATOR for c in columns if not c.flex)
        has_flex = any(c.flex for c in columns)
        room = width - fixed
        if not has_flex or room >= message_min(width):
            break
        droppable = [c for c in columns if not c.flex and c.drop_order < 99]
        if not droppable:
            break
        columns.remove(min(droppable, key=lambda c: c.drop_order))
    placed: list[PlacedColumn] = []
    x = 0
    for column in columns:
        cell = max(room, 8) if column.flex else sized(column)
        placed.append(PlacedColumn(column, x, cell))
        x += cell + SEPARATOR
    return tuple(placed)
