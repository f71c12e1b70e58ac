"""What the warehouse said to a batch sent: taken, try again (when), or refused for good; and
``WarehouseError``: it could not be reached or could not answer."""

from __future__ import annotations

import email.utils
import time
from dataclasses import dataclass

#: The longest ``Retry-After`` honoured: a store asking for more is asked again after this.
MAX_RETRY_AFTER_S = 300.0


@dataclass(frozen=True)
class Outcome:
    """The answer to one batch.

    ``taken``: the warehouse has it (delete it from the spool). Otherwise ``retry``: send it
    again later, not before ``retry_after`` seconds when the warehouse said so; else it was
    refused for good (a malformed batch: it is dropped, counted as lost). ``rejected``: records
    of a taken batch the warehouse said it dropped (OTLP's partial success). ``problem``: what
    went wrong, in a line."""

    taken: bool
    retry: bool = False
    retry_after: float | None = None
    rejected: int = 0
    problem: str = ""
    #: The batch is too large for the warehouse: send it in smaller parts.
    too_large: bool = False


TAKEN = Outcome(True)


class WarehouseError(Exception):
    """The warehouse could not be reached or could not answer; the text says why, in a line."""


def retry_after_seconds(value: str | None, now: float | None = None) -> float | None:
    """An HTTP ``Retry-After`` (seconds, or an HTTP date) in seconds from now, at most
    ``MAX_RETRY_AFTER_S``; None when absent or unreadable."""
    if not value:
        return None
    text = value.strip()
    if text.isdigit():
        return min(float(text), MAX_RETRY_AFTER_S)
    try:
        when = email.utils.parsedate_to_datetime(text)
    except (TypeError, ValueError, IndexError):
        return None
    if when is None:
        return None
    seconds = when.timestamp() - (time.time() if now is None else now)
    return min(max(seconds, 0.0), MAX_RETRY_AFTER_S)
