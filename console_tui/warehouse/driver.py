"""clickhouse-connect, the one driver of ClickHouse and chDB here, and its errors in a line."""

from __future__ import annotations

import logging
import re
from typing import Any

from .outcome import WarehouseError


def clickhouse_driver() -> Any:
    """clickhouse-connect, its logging kept off the screen; ``WarehouseError`` without the extra."""
    # The driver (and urllib3 under it) logs what it also raises, on standard error: under
    # the console's screen.
    for name in ("clickhouse_connect", "urllib3.connectionpool"):
        quiet = logging.getLogger(name)
        quiet.propagate = False
        quiet.addHandler(logging.NullHandler())
    try:
        import clickhouse_connect
    except ImportError as error:
        raise WarehouseError(
            f"ClickHouse and chDB need the [store] extra: pip install 'console-tui[store]' ({error})"
        ) from None
    return clickhouse_connect


def describe(error: BaseException) -> str:
    """An error of the driver or the engine in one line, without its stack or version trailer."""
    if isinstance(error, WarehouseError):  # said already (the chDB process's)
        return str(error)
    text = " ".join(str(error).split())
    if "UNKNOWN_TABLE" in text or "UNKNOWN_DATABASE" in text:
        return "no such table (nothing was shipped there yet?)"
    system = re.search(r"\[Errno -?\d+\] ([^\"')]+)", text)
    if system:
        return system.group(1).strip()
    text = text.split(" In scope ", 1)[0].split(" Stack trace", 1)[0]
    lowered = text.lower()
    if (
        "another server instance" in lowered
        or "cannot lock file" in lowered
        or "initializing embeddedserver" in lowered
    ):
        return "the directory is in use by another process (chDB opens a directory in one process at a time)"
    return f"{type(error).__name__}: {text}"[:300]
