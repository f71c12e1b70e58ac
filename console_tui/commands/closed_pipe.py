"""Standard output whose reader went away (``| head -1``, ``| true``): a command ends at
once and quietly, with status 0, as ``tail`` on files and the classic Unix tools do."""

from __future__ import annotations

import functools
import os
import select
import sys
from collections.abc import Callable
from typing import TypeVar

Main = TypeVar("Main", bound=Callable[..., int])


def reader_gone(fd: int) -> bool:
    """Whether the pipe (or terminal) on ``fd`` has no reader any more, without writing to
    it: a command that prints seldom (the live stream of a quiet graph) ends when ``head``
    has had enough, not at its next line."""
    try:
        poller = select.poll()
        poller.register(fd, 0)  # errors and hang-ups are always reported
        return any(events & (select.POLLERR | select.POLLHUP) for _fd, events in poller.poll(0))
    except (OSError, ValueError):
        return False


def quiet_stdout() -> None:
    """After a closed pipe: point stdout at /dev/null, so that Python's last flush at exit
    does not complain."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass


def quiet_on_closed_pipe(main: Main) -> Main:
    """``main`` with its output flushed before it returns; a closed pipe on stdout ends it
    with status 0 and no traceback."""

    @functools.wraps(main)
    def run(*args: object, **kwargs: object) -> int:
        try:
            status = main(*args, **kwargs)
            sys.stdout.flush()
        except (BrokenPipeError, ConnectionResetError):
            quiet_stdout()
            return 0
        return status

    return run  # type: ignore[return-value]
