"""The log warehouse in the table: its pages taken in, older ones asked for at the top, and
the rules handed down to it.

Each log warehouse given on the command line is a source (``sources.warehouse_source``) whose
thread asks the table and leaves what came in ``take()``; here, every intake tick, its first page of
a generation replaces what that source showed before, newer pages follow the tail as live
records do, and older pages are placed before the oldest rows (the cursor stays on its
record). Scrolling past the oldest row (``top_reached``) asks for the page before it; the
rules put in force (``Announcements.rules_changed``) are handed to each warehouse, which reads
its window again when what SQL can leave out changed. Nothing here waits for the warehouse.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, ClassVar, Protocol

from ...model.rules.ruleset import RuleSet
from ...model.store.late_records import Placed
from ...model.store.older_records import add_older, drop_source
from ...model.store.record_batch import RecordColumns
from ...system.freed_memory import give_back
from ..command_table import NAVIGATION, Command
from .context import ConsoleContext
from .intake import IntakeController

#: What a delivery of ``sources.warehouse_source`` says it is (kept as text: that module and the
#: warehouse's load only when a warehouse is given).
NEWEST, NEWER, OLDER = "newest", "newer", "older"


class Warehouse(Protocol):
    """A log warehouse source, as ``sources.warehouse_source.WarehouseSource`` is."""

    name: str
    generation: int
    at_start: bool

    def take(self) -> list[Any]: ...

    def ask(self, rules: RuleSet) -> bool: ...

    def ask_older(self) -> bool: ...


def warehouses_of(sources: Sequence[object]) -> list[Warehouse]:
    return [source for source in sources if callable(getattr(source, "ask_older", None))]  # type: ignore[misc]


class WarehouseController:
    """The log warehouses among the sources, their deliveries taken in each intake tick."""

    def __init__(
        self,
        context: ConsoleContext,
        intake: IntakeController,
        *,
        sources: Sequence[object],
        reapply_rules: Callable[[], None],
    ) -> None:
        c = context
        self._store, self._table, self._marks, self._changed = c.store, c.table, c.marks, c.changed
        self._intake = intake
        self.warehouses = warehouses_of(sources)
        #: The rules applied again to what the store holds (after a generation's rows went: the
        #: view's filtering of them, in the background, would hold the new rows back).
        self._reapply_rules = reapply_rules
        #: The generation each warehouse's rows in the store belong to.
        self._shown: dict[int, int] = {}
        if self.warehouses:
            c.announce.tick.subscribe(self.tick)
            c.announce.rules_changed.subscribe(self.rules_changed)

    def tick(self) -> None:
        """Take in what each warehouse delivered since the last tick; not while another screen
        is over the table's (a record's details, a dialog): it holds seqs that rows placed
        before would move."""
        if not self._table_shown():
            return
        for warehouse in self.warehouses:
            for delivery in warehouse.take():
                self._take(warehouse, delivery.kind, delivery.generation, delivery.columns)

    def _take(self, warehouse: Warehouse, kind: str, generation: int, columns: RecordColumns) -> None:
        key = id(warehouse)
        if kind == NEWEST:
            again = key in self._shown
            if again:  # read again: the rows of the generation before go
                self._drop(warehouse.name)
            self._shown[key] = generation
            if not len(self._store):
                self._intake.add_batches([columns])
            else:
                self._older(columns)
            if again:
                self._reapply_rules()
        elif self._shown.get(key) != generation:
            return
        elif kind == NEWER:
            self._intake.add_batches([columns], live_from=0)
        elif kind == OLDER:
            self._older(columns)
        self._changed()

    def _table_shown(self) -> bool:
        try:
            return self._table.screen.is_active
        except Exception:  # not mounted yet, or being taken down
            return False

    def _drop(self, source: str) -> None:
        marks = self._marks

        def drop() -> Placed | None:
            dropped = drop_source(self._store, source, marks)
            for seq in dropped.gone:
                marks.discard(seq)
            marks.move(dropped.moved)
            give_back()  # the rows of the generation before
            return Placed(self._store.first_seq, {}) if dropped.dropped else None

        self._intake.add_placed(drop)

    def _older(self, columns: RecordColumns) -> None:
        if not len(columns):
            return
        table = self._table
        cursor = None if table.following else table.cursor_seq
        marked = [*self._marks, *([cursor] if cursor is not None else [])]
        moved: dict[int, int] = {}

        def place() -> Any:
            placed = add_older(self._store, columns, marked)
            if placed is not None:
                moved.update(placed.moved)
            give_back()  # what reading and placing the page took
            return placed

        self._intake.add_placed(place)
        if cursor is not None and cursor in moved:
            table.jump_to_seq(moved[cursor])

    def top_reached(self) -> None:
        """The person went past the oldest row: ask each warehouse for the page before it."""
        if any([warehouse.ask_older() for warehouse in self.warehouses]):
            self._changed()

    def rules_changed(self, rules: RuleSet) -> None:
        for warehouse in self.warehouses:
            warehouse.ask(rules)

    def older_to_come(self) -> bool:
        """A warehouse has rows older than those it gave."""
        return any(not warehouse.at_start for warehouse in self.warehouses)

    COMMANDS: ClassVar[tuple[Command[WarehouseController], ...]] = (
        Command(
            "warehouse.older",
            top_reached,
            label="Older rows from the log warehouse",
            applies=older_to_come,
            group=NAVIGATION,
            about="The page before the oldest row (as Up, Page Up or Home on the oldest row ask for it)",
            words="clickhouse chdb history earlier page back",
        ),
    )
