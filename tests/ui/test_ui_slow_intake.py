"""The slower intake path (no take loop in C: no cc, no Python.h) is said once, at start, with
what it costs; the fast path says nothing."""

from __future__ import annotations

from types import SimpleNamespace

from console_tui.model.store.intake_queue import IntakeQueue
from console_tui.model.store.log_store import LogStore
from console_tui.model.store.record_batch import RecordColumns
from console_tui.sources.status import SourceStatus
from console_tui.ui.app import ConsoleApp

from support.feed import records
from support.ui import screen_text, until

NOTE = "no C compiler (cc)"


def reporting(status: SourceStatus) -> SimpleNamespace:
    """A live source that only reports ``status``."""
    return SimpleNamespace(status=status, start=lambda: None, stop=lambda: None)


def test_the_status_says_what_the_slower_path_costs():
    assert SourceStatus(path="c+cdr").slow_path_text() == ""
    assert SourceStatus(path="tcpros").slow_path_text() == ""
    text = SourceStatus(path="raw+cdr", path_note=NOTE).slow_path_text()
    assert text.startswith(f"slower intake: the take loop in C is not used ({NOTE})")
    assert "2-3 times the CPU a message" in text and "(cc)" in text and "(python3-dev)" in text


async def test_the_app_says_it_once_on_screen():
    queue = IntakeQueue()
    source = reporting(SourceStatus(origin="ROS 2 domain 7", path="raw+cdr", path_note=NOTE, running=True))
    app = ConsoleApp(store=LogStore(), queue=queue, sources=[source], utc=True)
    told = []
    notify = app.notify

    def counting_notify(message: str, **kwargs) -> None:
        told.append(message)
        notify(message, **kwargs)

    app.notify = counting_notify  # type: ignore[method-assign]
    async with app.run_test(size=(120, 40), notifications=True) as pilot:
        await until(pilot, lambda: "Slower intake" in screen_text(app), what="the slower path said")
        assert "the take loop in C is not used" in screen_text(app)
        for batch in range(3):  # more ticks with records: said once only
            queue.put(RecordColumns.from_records(records(5)))
            await until(pilot, lambda n=batch: f"{5 * (n + 1)}/{5 * (n + 1)} shown" in screen_text(app), what="rows")
    assert [message for message in told if "Slower intake" in message] == [told[0]]


async def test_the_fast_path_says_nothing():
    queue = IntakeQueue()
    source = reporting(SourceStatus(origin="ROS 2 domain 7", path="c+cdr", running=True))
    app = ConsoleApp(store=LogStore(), queue=queue, sources=[source], utc=True)
    async with app.run_test(size=(120, 40), notifications=True) as pilot:
        queue.put(RecordColumns.from_records(records(5)))
        await until(pilot, lambda: "5/5 shown" in screen_text(app), what="rows")
        assert "intake" not in screen_text(app).lower()
