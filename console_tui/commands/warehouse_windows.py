"""The log warehouse's windows in the headless commands (``tail``, ``convert``): each address
given read forward, its rows as record batches to merge with files by time, and what went
wrong said once (the command's exit status says it too)."""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Iterator, Sequence

from ..model.rules.ruleset import RuleSet
from ..model.store.record import LogRecord
from ..sources.warehouse_source import POLL_S, WindowReader
from ..warehouse.clickhouse import WarehouseError


class Windows:
    """The windows of ``args.warehouses`` (``location_options.apply_location_arguments``),
    read with ``rules`` going down into SQL; ``failed`` once one could not be read."""

    def __init__(
        self,
        args: argparse.Namespace,
        rules: RuleSet | None,
        complain: Callable[[str], None],
        *,
        max_rows: int | None,
        poll_s: float = POLL_S,
    ) -> None:
        self._complain = complain
        self.readers: list[WindowReader] = []
        self.failed = False
        self._poll_s = poll_s
        self._polled = time.monotonic()
        for address in args.warehouses:
            try:
                self.readers.append(
                    WindowReader(
                        address, since_ns=args.since_ns, until_ns=args.until_ns, rules=rules, max_rows=max_rows
                    )
                )
            except WarehouseError as error:
                self._fail(address.text, error)

    def _fail(self, where: str, error: WarehouseError) -> None:
        self._complain(f"the log warehouse at {where}: {error}")
        self.failed = True

    def streams(self) -> list[Iterator[list[LogRecord]]]:
        """Each window's records, oldest first, a page at a time."""
        return [self._records(reader) for reader in self.readers]

    def _records(self, reader: WindowReader) -> Iterator[list[LogRecord]]:
        try:
            for page in reader.pages():
                yield page.records()
        except WarehouseError as error:
            self._fail(reader.address.text, error)
            self.readers.remove(reader)

    def newer(self) -> list[LogRecord]:
        """The rows that came since, every ``poll_s`` (none between)."""
        now = time.monotonic()
        if now - self._polled < self._poll_s:
            return []
        self._polled = now
        found: list[LogRecord] = []
        for reader in list(self.readers):
            try:
                found.extend(reader.newer().records())
            except WarehouseError as error:  # said, and asked again at the next poll
                self._complain(f"the log warehouse at {reader.address.text}: {error}")
        found.sort(key=_stamp)
        return found

    def close(self) -> None:
        for reader in self.readers:
            reader.close()


def _stamp(record: LogRecord) -> int:
    return record.stamp_ns


def merged(streams: Sequence[Iterator[list[LogRecord]]]) -> Iterator[list[LogRecord]]:
    """Several sources' batches merged by time (one source: as it comes)."""
    from ..sources.files import merge_by_time

    if len(streams) == 1:
        return streams[0]
    return merge_by_time(list(streams)) if streams else iter(())
