"""Small helpers over ``concurrent.futures.Future``: settled futures, a step after a future, settling once."""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import Future
from typing import Any, TypeVar

T = TypeVar("T")


def settle(future: Future[Any], *, result: Any = None, error: BaseException | None = None) -> bool:
    """Give ``future`` its result or its error unless it has one already; always True."""
    if not future.done():
        if error is not None:
            future.set_exception(error)
        else:
            future.set_result(result)
    return True


def done_future(value: T) -> Future[T]:
    """A future that already holds ``value``."""
    future: Future[T] = Future()
    future.set_result(value)
    return future


def failed_future(error: BaseException) -> Future[Any]:
    """A future that already failed with ``error``."""
    future: Future[Any] = Future()
    future.set_exception(error)
    return future


def then(source: Future[Any], step: Callable[[Any], Any]) -> Future[Any]:
    """A future of ``step(source's result)``; a step returning a future is followed through.

    An error of ``source`` or of ``step`` becomes the error of the future returned. ``step``
    runs in the thread that completes ``source``.
    """
    out: Future[Any] = Future()

    def follow(inner: Future[Any]) -> None:
        error = inner.exception()
        settle(out, result=None if error else inner.result(), error=error)

    def done(finished: Future[Any]) -> None:
        error = finished.exception()
        if error is not None:
            settle(out, error=error)
            return
        try:
            value = step(finished.result())
        except Exception as failure:
            settle(out, error=failure)
            return
        if isinstance(value, Future):
            value.add_done_callback(follow)
        else:
            settle(out, result=value)

    source.add_done_callback(done)
    return out
